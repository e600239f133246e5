//! Intrinsic distance. The paper uses the biharmonic distance ([`mod@biharmonic`]) for sampling and
//! voting: cheap from the eigenbasis, smooth, and robust to noise.

pub mod biharmonic;

pub use biharmonic::{biharmonic, BiharmonicEmbedding};
