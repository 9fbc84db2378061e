//! A structure-aware scene generator: a tiny valid scene, then edits chosen by the
//! input bytes, each setting a documented key (`docs/config.md`) to a value at or past
//! its limits (zero, negative, NaN, huge, empty tables, wrong types), removing one,
//! adding a phase or a misspelt key, or making the scene 2D (a box of two lengths, so
//! that the 2D keys and the refusals of 3D-only ones are reached: [`FLAT`]), or making
//! it meshable and setting a mesh key (`mesh.rs`).
//! libFuzzer and proptest drive the same bytes.

use super::mesh::{MESHABLE, MESH_EDITS};
use super::pools::{NUMBERS, OTHERS, WORDS};

/// The input bytes, read one choice at a time (zeros once they run out).
pub struct Choices<'a> {
    data: &'a [u8],
    at: usize,
}

impl<'a> Choices<'a> {
    /// Choices read from `data`.
    pub fn new(data: &'a [u8]) -> Self {
        Self { data, at: 0 }
    }

    fn byte(&mut self) -> u8 {
        let b = self.data.get(self.at).copied().unwrap_or(0);
        self.at += 1;
        b
    }

    fn exhausted(&self) -> bool {
        self.at >= self.data.len()
    }

    fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[usize::from(self.byte()) % items.len()]
    }
}

/// Grain-law tables: each takes every family's keys.
const LAWS: [&str; 5] = ["size", "aspect_ratio", "b_over_a", "c_over_a", "c_over_b"];

/// Every table of a scene with its documented keys (`src/io/scene/raw.rs`).
const TABLES: [(&str, &[&str]); 11] = [
    ("", &["seed", "grains", "target_fraction"]),
    ("box", &["size", "boundary"]),
    ("phase", &["name", "share"]),
    (
        "law",
        &[
            "distribution",
            "value",
            "mean",
            "std",
            "sigma",
            "scale",
            "loc",
            "min",
            "max",
            "x",
            "cdf",
            "by",
            "interpolation",
        ],
    ),
    (
        "phase.orientation",
        &[
            "kind",
            "quaternion",
            "axis",
            "mean",
            "kappa",
            "min",
            "max",
            "direction",
            "spin_reference",
            "spin_kappa",
            "spin_mean",
            "angle",
        ],
    ),
    (
        "phase.texture",
        &[
            "kind",
            "quaternion",
            "euler",
            "crystal_direction",
            "sample_direction",
            "kappa",
            "file",
            "relative_to_shape",
        ],
    ),
    ("phase.elastic", &["E", "nu"]),
    ("phase.measured", &["file", "mode", "phase"]),
    (
        "packing",
        &[
            "max_steps",
            "jam_resolution",
            "rotation",
            "max_turn",
            "restore",
            "effort",
            "unjam",
            "gap",
            "time_limit",
        ],
    ),
    ("units", &["length", "stress"]),
    (
        "output",
        &[
            "dir",
            "grains_csv",
            "summary_json",
            "vtk",
            "vtk_resolution",
            "periodic_images",
            "centers",
            "rve",
            "rve_resolution",
            "rve_voxel_size",
            "rve_fill",
            "sections_png",
            "statistics_png",
            "packing_png",
            "damask",
            "abaqus",
            "mesh",
            "mesh_size",
            "mesh_order",
            "mesh_fill",
        ],
    ),
];

/// Free-form tables passed through to DAMASK, and the matrix's elastic constants.
const PASSED: [(&str, &[&str]); 4] = [
    ("phase.damask", &["lattice", "mechanical", "type"]),
    ("matrix.elastic", &["E", "nu"]),
    ("matrix.damask", &["lattice", "type"]),
    ("homogenization", &["name", "N_constituents", "mechanical"]),
];

/// 2D scenes: the boxes of two lengths an edit sets, each with one of [`FLAT_SETS`].
const FLAT: [&str; 3] = ["[20.0, 20.0]", "[24.0, 14.0]", "[9.0, 30.0]"];

/// What a 2D edit sets beside the box (table, key, value): the 2D orientations, the
/// 2D limit of the fraction (π/√12 = 0.90690) at and past it, a size table by area
/// (`by = "area"`, 2D only), and the 3D-only keys a 2D scene refuses (mixed 2D/3D
/// scenes).
const FLAT_SETS: [&[(&str, &str, &str)]; 11] = [
    &[],
    &[
        ("phase.orientation", "kind", "\"vonmises\""),
        ("phase.orientation", "kappa", "2.0"),
        ("phase.orientation", "mean", "30.0"),
    ],
    &[
        ("phase.orientation", "kind", "\"aligned\""),
        ("phase.orientation", "angle", "-45.0"),
    ],
    &[
        ("phase.aspect_ratio", "distribution", "\"uniform\""),
        ("phase.aspect_ratio", "min", "1.0"),
        ("phase.aspect_ratio", "max", "2.5"),
    ],
    &[("", "grains", ""), ("", "target_fraction", "0.90690")],
    &[("", "grains", ""), ("", "target_fraction", "0.9070")],
    &[("phase.orientation", "kind", "\"fisher\"")],
    &[
        ("phase.b_over_a", "distribution", "\"constant\""),
        ("phase.b_over_a", "value", "0.5"),
    ],
    &[("packing", "rotation", "\"axis\"")],
    &[
        ("phase.orientation", "kind", "\"tilt\""),
        ("phase.orientation", "axis", "\"x\""),
        ("phase.orientation", "kappa", "1.0"),
    ],
    &[
        ("phase.size", "distribution", "\"table\""),
        ("phase.size", "value", ""),
        ("phase.size", "x", "[2.0, 3.0, 4.0]"),
        ("phase.size", "cdf", "[0.0, 0.5, 1.0]"),
        ("phase.size", "by", "\"area\""),
    ],
];

/// One `key = value` line in table `table` (`phase.size` etc. are those of phase
/// `phase`).
#[derive(Clone)]
struct Entry {
    table: String,
    phase: usize,
    key: String,
    value: String,
}

/// A scene text from `choices`: the tiny valid scene below, then up to 24 edits.
pub fn scene_from_choices(choices: &mut Choices) -> String {
    let entry = |table: &str, phase, key: &str, value: &str| Entry {
        table: table.into(),
        phase,
        key: key.into(),
        value: value.into(),
    };
    let mut entries = vec![
        entry("", 0, "seed", "1"),
        entry("", 0, "grains", "4"),
        entry("box", 0, "size", "[20.0, 20.0, 20.0]"),
        entry("phase.size", 0, "distribution", "\"constant\""),
        entry("phase.size", 0, "value", "3.0"),
    ];
    let mut phases = 1;
    for _ in 0..24 {
        if choices.exhausted() {
            break;
        }
        match choices.byte() % 10 {
            0..=3 => {
                let (table, keys) = choices.pick(&TABLES);
                let table = match table {
                    "law" => format!("phase.{}", choices.pick(&LAWS)),
                    t => t.to_owned(),
                };
                set(&mut entries, table, choices, keys, phases);
            }
            4 => {
                let (table, keys) = choices.pick(&PASSED);
                set(&mut entries, table.to_owned(), choices, keys, phases);
            }
            5 if !entries.is_empty() => {
                let i = usize::from(choices.byte()) % entries.len();
                entries.remove(i);
            }
            6 if phases < 3 => {
                // A second phase: the first one's entries again, to be edited apart.
                let first: Vec<Entry> = (entries.iter())
                    .filter(|e| e.table.starts_with("phase") && e.phase == 0)
                    .cloned()
                    .collect();
                entries.extend(first.into_iter().map(|e| Entry { phase: phases, ..e }));
                phases += 1;
            }
            8 => {
                // 2D: a box of two lengths, and one of the 2D edits.
                let size = choices.pick(&FLAT);
                entries.retain(|e| !(e.table == "box" && e.key == "size"));
                entries.push(entry("box", 0, "size", size));
                let phase = usize::from(choices.byte()) % phases;
                for &(table, key, value) in choices.pick(&FLAT_SETS) {
                    entries.retain(|e| !(e.table == table && e.key == key && e.phase == phase));
                    // An empty value removes the key.
                    if !value.is_empty() {
                        entries.push(entry(table, phase, key, value));
                    }
                }
            }
            9 => {
                // A meshable scene (`mesh.rs`: materials on every phase), then one mesh
                // key set at or past its limits, or removed (an empty value).
                let (table, key, values) = choices.pick(&MESH_EDITS);
                let edit = (table, key, choices.pick(values));
                let phase = usize::from(choices.byte()) % phases;
                let base = MESHABLE
                    .into_iter()
                    .flat_map(|e| (0..phases).map(move |p| (e, p)));
                for ((t, k, v), p) in base.chain([(edit, phase)]) {
                    entries.retain(|e| !(e.table == t && e.key == k && e.phase == p));
                    if !v.is_empty() {
                        entries.push(entry(t, p, k, v));
                    }
                }
                // The grains fill has no matrix: its `[matrix]` would be refused.
                if edit == ("output", "mesh_fill", "\"grains\"") {
                    entries.retain(|e| !e.table.starts_with("matrix"));
                }
            }
            _ => {
                // A misspelt or misplaced key, or a key given twice.
                let e = entries.get(usize::from(choices.byte()) % entries.len().max(1));
                let mut e = e.cloned().unwrap_or_else(|| entry("", 0, "seed", "1"));
                match choices.byte() % 3 {
                    0 => e.key.push('s'),
                    1 => e.table = choices.pick(&TABLES).0.replace("law", "phase.size"),
                    _ => {}
                }
                entries.push(e);
            }
        }
    }
    render(&entries, phases)
}

/// Sets `key` (one of `keys`) of `table` to a value from the pools.
fn set(entries: &mut Vec<Entry>, table: String, c: &mut Choices, keys: &[&str], phases: usize) {
    let key = c.pick(keys).to_owned();
    let value = match c.byte() % 3 {
        0 => c.pick(&NUMBERS),
        1 => c.pick(&OTHERS),
        _ => c.pick(&WORDS),
    }
    .to_owned();
    let phase = usize::from(c.byte()) % phases;
    entries.retain(|e| !(e.table == table && e.key == key && e.phase == phase));
    entries.push(Entry {
        table,
        phase,
        key,
        value,
    });
}

/// The TOML text: top-level keys, `[box]`, each `[[phase]]` with its sub-tables, then
/// the other tables, each key under its table header.
fn render(entries: &[Entry], phases: usize) -> String {
    let mut text = String::new();
    let mut section = |header: &str, table: &str, phase: usize| {
        let lines: Vec<String> = (entries.iter())
            .filter(|e| e.table == table && e.phase == phase)
            .map(|e| format!("{} = {}\n", e.key, e.value))
            .collect();
        if !lines.is_empty() || header.starts_with("[[") {
            text.push_str(header);
            text.extend(lines);
        }
    };
    section("", "", 0);
    section("[box]\n", "box", 0);
    for p in 0..phases {
        section("[[phase]]\n", "phase", p);
        for sub in LAWS
            .iter()
            .chain(&["orientation", "texture", "elastic", "damask"])
        {
            let table = format!("phase.{sub}");
            section(&format!("[{table}]\n"), &table, p);
        }
        section("[phase.measured]\n", "phase.measured", p);
    }
    for table in [
        "packing",
        "units",
        "output",
        "matrix.elastic",
        "matrix.damask",
        "homogenization",
    ] {
        section(&format!("[{table}]\n"), table, 0);
    }
    text
}
