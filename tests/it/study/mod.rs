//! `aster study` end to end: a small grid of our scenes, the CSV, the markdown table and the plots.
mod grid;
