//! Heat conduction end to end: Code_Aster's own thermal verification cases run unmodified (THER_LINEAIRE,
//! THER_NON_LINE, their loads and fields), the loads against closed forms, the temperature into mechanics
//! (AFFE_VARC), and scenes of our own with analytic answers and their orders of
//! convergence in h and Δt.
mod analytic;
mod corpus;
mod loads;
mod orthotropic;
mod thermo_mech;
