//! DEBUT and FIN: their options only tune Code_Aster's own runtime (test mode CODE, DEBUG output, the
//! error mode ERREUR, IGNORE_ALARM, memory and PAR_LOT); none changes what is computed, so they are
//! taken as read. The run state they mark is handled by the runner.

use crate::catalog::args::Args;
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::stages::Ctx;

pub fn nothing(_ctx: &mut Ctx, args: &Args) -> Result<Option<ConceptData>> {
    args.read_all();
    Ok(None)
}
