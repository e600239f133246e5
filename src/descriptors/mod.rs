//! Point descriptors. The paper's good-voter test compares wave kernel signatures ([`mod@wks`]);
//! the geodesic polish also compares band-limited mean curvature ([`curvature`]).

pub mod curvature;
pub mod wks;

pub use wks::{wks, WksParams};
