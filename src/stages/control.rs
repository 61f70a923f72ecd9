//! DEBUT and FIN: their options only tune Code_Aster's own runtime; the run
//! state they mark is handled by the runner.

use crate::catalog::args::Args;
use crate::concepts::ConceptData;
use crate::diag::Result;
use crate::stages::Ctx;

pub fn nothing(_ctx: &mut Ctx, _args: &Args) -> Result<Option<ConceptData>> {
    Ok(None)
}
