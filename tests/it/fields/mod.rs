//! Fields and results made of fields: CREA_RESU (AFFE of fields of reals and of functions of X, Y, Z and
//! INST, reuse, ASSE, PROL_RTZ) and CREA_CHAMP's fields of functions on nodes (NOEU_TEMP_F, NOEU_NEUT_F)
//! with their EVAL; Code_Aster's corpus cases run unmodified and scenes of our own against closed forms.
mod crea_champ_asse;
mod crea_resu;
