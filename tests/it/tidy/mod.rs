//! Tidy tests of the tree itself: the architecture's use rules (docs/ARCHITECTURE.md) and the generated
//! docs/SUPPORTED.md.
mod architecture;
mod docs;
