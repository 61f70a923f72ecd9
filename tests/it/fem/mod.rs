//! The finite-element core: patch tests of every cell type and modelisation, located errors of the
//! solving stages, von Mises plasticity against closed forms and the corpus, POST_RELEVE_T's nodal
//! averaging, MACR_LIGN_COUPE's values along lines against a linear displacement and a homogeneous
//! stress, POST_ERREUR's norms against hand computations, and the answers users reported wrong or
//! silent (`reported`).
mod archivage;
mod fe_errors;
mod lign_coupe;
mod patch;
mod plasticity;
mod post_erreur;
mod post_releve;
mod reported;
