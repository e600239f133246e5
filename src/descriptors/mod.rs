//! Point descriptors. The paper's good-voter test compares wave kernel signatures ([`wks`]).

pub mod wks;

pub use wks::{wks, WksParams};
