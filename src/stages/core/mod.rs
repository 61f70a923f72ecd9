//! The core every solving stage shares (MECA_STATIQUE, STAT_NON_LINE, the X-FEM driver and the coupled
//! drivers to come): function evaluation at a point and time (`eval`), the checked problem of a model and a
//! material field (`problem`), the loads and conditions of EXCIT and the reduced assembled system
//! (`assembly`), SOLVEUR and the solve (`solver`), and the Newton / time-step loop with Code_Aster's
//! convergence keywords (`newton`). It knows no command: it reads `Args` of the solving commands only
//! through the keywords they share (EXCIT, SOLVEUR, CONVERGENCE, INCREMENT).

pub mod assembly;
pub mod eval;
pub mod hm;
pub mod newton;
pub mod problem;
pub mod solver;
