//! The solving commands: MECA_STATIQUE (`statics`), STAT_NON_LINE (`nonlinear`), and both on X-FEM models
//! (`xfem`), THER_LINEAIRE and THER_NON_LINE (`thermal`), all on the shared core of `stages::core`.

pub mod hm;
pub mod list_inst;
pub mod nonlinear;
pub mod statics;
pub mod thermal;
pub mod xfem;

pub use list_inst::defi_list_inst;
pub use nonlinear::stat_non_line;
pub use statics::meca_statique;
pub use thermal::{ther_lineaire, ther_non_line};
