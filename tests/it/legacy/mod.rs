//! Real command files end to end: the legacy suite of ../shared/astest (catalogue check of every file, the
//! conformance run against tests/passing.txt), rung (b) variants, WTNV149 and our own scenes of comm/.
mod astest;
mod rung_b;
mod scenes;
mod wtnv149;
