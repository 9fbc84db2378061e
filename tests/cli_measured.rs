//! End-to-end tests of measured grain tables (`[phase.measured]`, issue 15): exactly
//! the table's grains or drawn from it, crystal orientations kept, mixed with drawn
//! phases, a grains.csv round trip; and bad tables.

mod support;

use std::path::Path;
use support::files::{files_in, pack_in, pack_ok, repo};
use support::packed::{pack_and_check, read_grains};

#[test]
fn measured_table_packs_exactly_its_grains_and_round_trips() {
    let dir = support::files::scratch("shapes", "measured");
    let summary = pack_and_check(&dir, &repo("configs/measured_grains.toml"), true, 0);
    let table = read_grains(Path::new(&repo("configs/measured_grains.csv")));
    let packed = read_grains(&dir.join("out/grains.csv"));
    assert_eq!(summary["grains"], 200);
    // Exactly the table's grains, shapes and orientations bit for bit (grains are
    // written with 17 digits and orientations kept: no rotation).
    assert_eq!(table.len(), packed.len());
    for (t, p) in table.iter().zip(&packed) {
        assert_eq!(t.semi_axes, p.semi_axes);
        assert_eq!(t.rotation, p.rotation);
    }
    // The box follows from target_fraction: Σ volumes / (Lx Ly Lz) = 0.5, to the
    // rounding of a sum of 200 volumes and a cube root (1e-12 relative).
    let fraction = summary["packing_fraction"].as_f64().unwrap();
    assert!((fraction - 0.5).abs() < 1e-12, "{fraction}");
    // The packed diameters are the table's: KS distance 0 against its step CDF.
    assert_eq!(summary["phases"][0]["diameter"]["ks_distance"], 0.0);
    // And their shapes the table's: a1/a2 against the table's own a1/a2.
    assert_eq!(summary["phases"][0]["aspect_ratio"]["ks_distance"], 0.0);

    // Round trip: the packed grains.csv, read back and drawn from with replacement.
    std::fs::write(
        dir.join("again.toml"),
        "seed = 9\ngrains = 150\n[box]\nsize = [50.0, 50.0, 50.0]\n[[phase]]\n\
         measured = { file = \"out/grains.csv\", phase = 0 }\n",
    )
    .unwrap();
    pack_ok(&dir, &["again.toml", "--out", "again", "--quiet"]);
    let again = read_grains(&dir.join("again/grains.csv"));
    assert_eq!(again.len(), 150);
    for g in &again {
        assert!(table.iter().any(|t| t.semi_axes == g.semi_axes), "{g:?}");
    }
}

#[test]
fn bad_measured_tables_name_line_and_column_and_write_nothing() {
    let scene = "seed = 1\ngrains = 3\n[box]\nsize = [40.0, 40.0, 40.0]\n[[phase]]\n\
                 measured = { file = \"t.csv\" }\n";
    for (csv, want) in [
        ("d\n3.0\n-1.0\n", "t.csv:3: d = -1"),
        ("a1,a2,a3\n3,2,1\n3,2,abc\n", "t.csv:3: a3 = abc"),
        ("a1,a2,a3,qw,qx,qy,qz\n3,2,1,0.9,0,0,0\n", "t.csv:2: qw"),
        ("size\n3\n", "t.csv:1: (header)"),
    ] {
        let dir = support::files::scratch("shapes", "badcsv");
        std::fs::write(dir.join("s.toml"), scene).unwrap();
        std::fs::write(dir.join("t.csv"), csv).unwrap();
        let run = pack_in(&dir, &["s.toml", "--out", "out"]);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{err}");
        assert!(err.contains(want), "want {want} in: {err}");
        assert_eq!(files_in(&dir), ["s.toml", "t.csv"]);
    }
}

/// The named columns of a CSV file, as written (strings, so equal means bit for bit).
fn csv_columns(path: &Path, names: &[&str]) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let at: Vec<usize> = names
        .iter()
        .map(|n| header.iter().position(|h| h == n).unwrap())
        .collect();
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            at.iter().map(|&i| f[i].to_string()).collect()
        })
        .collect()
}

#[test]
fn measured_table_keeps_the_crystal_orientations_of_a_packed_grains_csv() {
    let dir = support::files::scratch("shapes", "crystals");
    let scene = repo("configs/measured_grains.toml");
    pack_ok(&dir, &[&scene, "--out", "first", "--quiet"]);
    let crystal = ["o0", "o1", "o2", "o3"];
    let first = csv_columns(&dir.join("first/grains.csv"), &crystal);
    // Exactly the same grains again: each keeps its crystal orientation, bit for bit.
    std::fs::write(
        dir.join("exact.toml"),
        "seed = 2\ntarget_fraction = 0.4\n[box]\nsize = [1.0, 1.0, 1.0]\n[[phase]]\n\
         measured = { file = \"first/grains.csv\", mode = \"exact\" }\n",
    )
    .unwrap();
    pack_ok(&dir, &["exact.toml", "--out", "exact", "--quiet"]);
    assert_eq!(csv_columns(&dir.join("exact/grains.csv"), &crystal), first);
    // Its texture is measured against the table's own crystals (not the default random
    // law): the same orientations, so the KS distance is 0.
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("exact/summary.json")).unwrap())
            .unwrap();
    let texture = &summary["textures"][0];
    assert_eq!(texture["kind"], "measured");
    assert_eq!(texture["file_rows"].as_u64(), Some(first.len() as u64));
    let ks = texture["ks_distance"].as_f64().unwrap();
    assert!(ks < 1e-12, "{ks}");
    // Drawn with replacement: every grain carries its row's shape and crystal together.
    std::fs::write(
        dir.join("draw.toml"),
        "seed = 5\ngrains = 120\n[box]\nsize = [50.0, 50.0, 50.0]\n[[phase]]\n\
         measured = { file = \"first/grains.csv\" }\n",
    )
    .unwrap();
    pack_ok(&dir, &["draw.toml", "--out", "draw", "--quiet"]);
    let both = ["a1", "a2", "a3", "o0", "o1", "o2", "o3"];
    let rows = csv_columns(&dir.join("first/grains.csv"), &both);
    let drawn = csv_columns(&dir.join("draw/grains.csv"), &both);
    assert_eq!(drawn.len(), 120);
    for g in &drawn {
        assert!(rows.contains(g), "{g:?} is no row of the table");
    }
    // A table of Bunge Euler angles (degrees) reads back to the same angles, to the
    // rounding of a quaternion round trip (1e-9 degrees).
    std::fs::write(
        dir.join("euler.csv"),
        "d,phi1,Phi,phi2\n4.0,10.0,20.0,30.0\n5.0,200.0,95.0,300.0\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("euler.toml"),
        "seed = 1\ngrains = 2\n[box]\nsize = [40.0, 40.0, 40.0]\n[[phase]]\n\
         measured = { file = \"euler.csv\", mode = \"exact\" }\n",
    )
    .unwrap();
    pack_ok(&dir, &["euler.toml", "--out", "euler", "--quiet"]);
    let angles = csv_columns(&dir.join("euler/grains.csv"), &["phi1", "Phi", "phi2"]);
    let want = [[10.0, 20.0, 30.0], [200.0, 95.0, 300.0]];
    for (got, want) in angles.iter().zip(want) {
        for (g, w) in got.iter().zip(want) {
            let g: f64 = g.parse().unwrap();
            assert!((g - w).abs() < 1e-9, "{got:?} vs {want:?}");
        }
    }
    // A texture on a phase whose table gives the crystals is refused.
    std::fs::write(
        dir.join("both.toml"),
        "seed = 1\ngrains = 2\n[box]\nsize = [40.0, 40.0, 40.0]\n[[phase]]\n\
         measured = { file = \"euler.csv\", mode = \"exact\" }\n\
         texture = { kind = \"random\" }\n",
    )
    .unwrap();
    let run = pack_in(&dir, &["both.toml", "--out", "both"]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(err.contains("phase[0].texture"), "{err}");
}

#[test]
fn exact_and_drawn_phases_mix_by_volume_share() {
    let dir = support::files::scratch("shapes", "mixed");
    std::fs::copy(repo("configs/measured_grains.csv"), dir.join("t.csv")).unwrap();
    // The exact table is share 1 of 3: the drawn phase adds twice its volume.
    let scene = "seed = 4\ntarget_fraction = 0.35\n[box]\nsize = [1.0, 1.0, 1.0]\n\
                 [[phase]]\nname = \"table\"\nmeasured = { file = \"t.csv\", mode = \"exact\" }\n\
                 [[phase]]\nname = \"drawn\"\nshare = 2.0\n\
                 size = { distribution = \"uniform\", min = 4.0, max = 6.0 }\n";
    std::fs::write(dir.join("mixed.toml"), scene).unwrap();
    let summary = pack_and_check(&dir, "mixed.toml", true, 0);
    let table = read_grains(&dir.join("t.csv"));
    let packed = read_grains(&dir.join("out/grains.csv"));
    // Exactly the table's 200 grains, in order, then the drawn ones.
    let exact: Vec<_> = packed.iter().filter(|g| g.phase == 0).collect();
    assert_eq!(exact.len(), table.len());
    for (t, p) in table.iter().zip(&exact) {
        assert_eq!(t.semi_axes, p.semi_axes);
    }
    // Volumes 1 : 2 within one drawn grain (at most (π/6)·6³ = 113 of ~2·8000).
    let volume = |phase: usize| -> f64 {
        packed
            .iter()
            .filter(|g| g.phase == phase)
            .map(|g| g.volume())
            .sum()
    };
    let (v0, v1) = (volume(0), volume(1));
    let grain_max = std::f64::consts::PI / 6.0 * 216.0;
    assert!((v1 - 2.0 * v0).abs() <= grain_max, "{v0} {v1}");
    // The box holds them at the target, within half a drawn grain's volume.
    let size: Vec<f64> = summary["box"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let box_volume: f64 = size.iter().product();
    assert!(((v0 + v1) / box_volume - 0.35).abs() <= 0.5 * grain_max / box_volume);
    assert!(
        (size[0] - size[1]).abs() < 1e-9 * size[0],
        "a cube stays a cube"
    );
    // A grain count cannot be honoured by a mixed scene: a named error.
    std::fs::write(
        dir.join("count.toml"),
        scene.replace("target_fraction = 0.35", "grains = 400"),
    )
    .unwrap();
    let run = pack_in(&dir, &["count.toml", "--out", "count"]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(
        err.contains("count.toml") && err.contains("grains"),
        "{err}"
    );
    assert!(!dir.join("count").exists());
}
