use intrinsym::shapes;
fn main() {
    for (name, c) in [("rest", shapes::quadruped(5, shapes::Pose::Rest, 0.0, 0)), ("walk", shapes::quadruped(5, shapes::Pose::Walking, 0.0, 1)), ("walknoise", shapes::quadruped(5, shapes::Pose::Walking, 0.002, 1)), ("star5", shapes::star(5, 5))] {
        let m = &c.mesh;
        let missing = c.mirror.iter().filter(|&&x| x == u32::MAX).count();
        let limb_counts: Vec<usize> = (0..c.limbs.len()).map(|j| c.limb.iter().filter(|&&l| l == j).count()).collect();
        println!("{name}: n={} area={:.3} diag={:.3} missing-mirror={} limbs={:?} degenerate={}", m.num_vertices(), m.area(), m.bbox_diagonal(), missing, limb_counts, m.info.degenerate_triangles);
        intrinsym::mesh::write_off(format!("/tmp/{name}.off"), &m.vertices, &m.triangles).unwrap();
    }
}
