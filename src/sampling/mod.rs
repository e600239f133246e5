//! Point selection (paper §4.1): farthest point sampling in biharmonic space.

pub mod farthest_point;

pub use farthest_point::{farthest_point, Samples};
