//! Fields: CALC_CHAMP (fields computed from a result; `thermal` on thermal results), CREA_CHAMP (fields of
//! their own) and MODI_REPERE (fields in another frame).

pub mod calc_champ;
pub mod crea_champ;
pub mod hm;
pub mod repere;
pub mod thermal;

pub use calc_champ::calc_champ;
pub use crea_champ::crea_champ;
pub use repere::modi_repere;
