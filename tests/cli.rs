//! The command-line tool's argument checks (writes only under the build folder's
//! `CARGO_TARGET_TMPDIR`).

use std::process::Command;

fn intrinsym(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_intrinsym")).args(args).output().expect("run intrinsym");
    (out.status.code().unwrap_or(-1), String::from_utf8_lossy(&out.stdout).into_owned(), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// `generate` takes a size per shape: an icosphere level (default 5) for the animals, spheres
/// and the star, a grid size (default 34) for the torus. Before, one default (34) served both,
/// and `generate quadruped q.off` asked for an icosphere of level 34: the machine's 24 GiB were
/// gone within minutes. A size out of a shape's range is a usage error naming `--size` and the
/// range, and writes nothing.
#[test]
fn generate_sizes_have_per_shape_defaults_and_ranges() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli_generate");
    std::fs::create_dir_all(&dir).unwrap();
    let path = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let (code, stdout, _) = intrinsym(&["generate", "quadruped", &path("q.off")]);
    assert_eq!(code, 0);
    assert!(stdout.contains("(10242 vertices)"), "{stdout}");
    let (code, stdout, _) = intrinsym(&["generate", "torus", &path("t.off")]);
    assert_eq!(code, 0);
    assert!(stdout.contains(&format!("({} vertices)", 3 * 34 * 34)), "{stdout}");
    for (shape, size, range) in [("quadruped", "9", "from 0 to 8"), ("icosphere", "40", "from 0 to 8"), ("torus", "2", "from 3 to 1000"), ("torus", "5000", "from 3 to 1000")] {
        let file = path(&format!("{shape}_{size}.off"));
        let (code, _, stderr) = intrinsym(&["generate", shape, &file, "--size", size]);
        assert_eq!(code, 2, "{shape} --size {size}: {stderr}");
        assert!(stderr.contains(&format!("--size {size}")) && stderr.contains(range), "{stderr}");
        assert!(!std::path::Path::new(&file).exists());
    }
}
