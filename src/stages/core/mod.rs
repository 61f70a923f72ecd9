//! The core every solving command shares, whatever its physics: the shared keywords read once into typed
//! settings, the physics chosen there (`settings`); the loads of EXCIT handed to the physics as typed items
//! (`loads`); the time stepping, prediction and Newton corrections over any `fem::physics::Physics`
//! (`driver`); Code_Aster's convergence keywords, instants and archiving (`newton`); SOLVEUR and the
//! solver's log (`solver`); function evaluation at a point and time (`eval`); and the builders of the
//! physics from concepts: the elastic problem (`problem`), the saturated HM one (`hm`) and heat conduction
//! (`heat`); and what results made of stored fields share (`stored`: LIRE_RESU, CREA_RESU).

pub mod driver;
pub mod eval;
pub mod heat;
pub mod hm;
pub mod loads;
pub mod newton;
pub mod problem;
pub mod settings;
pub mod solver;
pub mod stored;
