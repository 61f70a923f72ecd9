//! The finite-element core: patch tests of every cell type and modelisation, located errors of the
//! solving stages, POST_RELEVE_T's nodal averaging, POST_ERREUR's norms against hand computations.
mod fe_errors;
mod patch;
mod post_erreur;
mod post_releve;
