//! # rccpack
//!
//! Learn spatial placement rules from a few demonstrations and lay out new
//! objects that keep them.
#![warn(missing_docs)]

pub mod bench;
pub mod eval;
pub mod relations;
pub mod render;
pub mod rules;
pub mod scene;
pub mod synth;
