//! What the front ends write: the JSON report ([`json`]), a coloured PLY with per-vertex
//! quality ([`ply`]), and the SVG/HTML picture of the symmetry space ([`report`]).

pub mod json;
pub mod ply;
pub mod report;

/// Distinct, readable colours for groups and regions (Tableau 10).
pub const PALETTE: [[u8; 3]; 10] = [
    [78, 121, 167],
    [242, 142, 43],
    [225, 87, 89],
    [118, 183, 178],
    [89, 161, 79],
    [237, 201, 72],
    [176, 122, 161],
    [255, 157, 167],
    [156, 117, 95],
    [186, 176, 172],
];
