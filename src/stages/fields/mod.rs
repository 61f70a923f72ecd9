//! Fields: CALC_CHAMP (fields computed from a result; `thermal` on thermal results), CREA_CHAMP (fields of
//! their own), MODI_REPERE (fields in another frame) and CREA_RESU (results made of fields).

pub mod calc_champ;
pub mod crea_champ;
pub mod crea_resu;
pub mod hm;
pub mod repere;
pub mod thermal;

pub use calc_champ::calc_champ;
pub use crea_champ::crea_champ;
pub use crea_resu::crea_resu;
pub use repere::modi_repere;
