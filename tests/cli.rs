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

/// `detect`'s settings take the C API's ranges (`sym_params_set_*`): a value outside is a
/// usage error naming the option and the range, before the mesh is read. Before, `--samples 0`
/// and `--hierarchy-vertices 10` ran and reported no symmetry, and `-k 0` was ignored.
#[test]
fn detect_settings_out_of_range_are_usage_errors() {
    let missing = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli_detect_never_read.off");
    let input = missing.to_string_lossy().into_owned();
    for (flag, value, range) in [
        ("-k", "0", "from 3 to 1000"),
        ("--samples", "0", "from 8 to 1000"),
        ("--samples", "100000", "from 8 to 1000"),
        ("--restarts", "9", "from 0 to 8"),
        ("--groups", "65", "from 0 to 64"),
        ("--proxy-vertices", "10", "0 (off) or an integer from 1000 to 1000000"),
        ("--hierarchy-vertices", "10", "0 (off) or an integer from 1000 to 1000000"),
        ("--eps", "0", "greater than 0, at most 0.5"),
        ("--accept", "0.7", "greater than 0, at most 0.5"),
        ("--wks-quantile", "0", "greater than 0, at most 1"),
    ] {
        let (code, _, stderr) = intrinsym(&["detect", &input, flag, value]);
        assert_eq!(code, 2, "{flag} {value}: {stderr}");
        assert!(stderr.contains(flag) && stderr.contains(range) && !stderr.contains("No such file"), "{flag} {value}: {stderr}");
    }
    // In range, the same options pass parsing and the missing mesh is what fails.
    let (code, _, stderr) = intrinsym(&["detect", &input, "-k", "3", "--samples", "8", "--groups", "0", "--proxy-vertices", "0", "--hierarchy-vertices", "1000000"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(stderr.contains("cli_detect_never_read.off"), "{stderr}");
}

/// Outputs are checked before the detection: a report that is neither `.svg` nor `.html` is
/// a usage error (an SVG was written into `r.pdf` before), and an output whose folder does not
/// exist fails before the mesh is read (it failed after the whole detection, its result lost).
#[test]
fn outputs_are_checked_before_detecting() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli_outputs");
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join("never_read.off").to_string_lossy().into_owned();
    let (code, _, stderr) = intrinsym(&["detect", &input, "--report", &dir.join("r.pdf").to_string_lossy()]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("--report") && stderr.contains(".svg, .html or .htm"), "{stderr}");
    for flag in ["--json", "--ply", "--report"] {
        let out = dir.join("missing_folder").join("out.html").to_string_lossy().into_owned();
        let (code, _, stderr) = intrinsym(&["detect", &input, flag, &out]);
        assert_eq!(code, 1, "{flag}: {stderr}");
        assert!(stderr.contains("missing_folder") && stderr.contains("does not exist") && !stderr.contains("never_read"), "{flag}: {stderr}");
    }
}
