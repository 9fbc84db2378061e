//! The architecture of `docs/architecture.md`, checked on the source: each layer imports
//! only the layers below it, and no two modules of one folder import each other, directly
//! or round a longer cycle.
//!
//! The scan reads every `crate::…` and `super::…` path in code (comment lines skipped),
//! expands `{…}` groups, and resolves a name re-exported by a folder's `mod.rs` to the
//! module that defines it.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::Path;

/// Each layer and the layers it may import, bottom up.
const LAYERS: &[(&str, &[&str])] = &[
    ("contact", &[]),
    ("octree", &[]),
    ("laws", &[]),
    ("scene", &["contact", "octree", "laws"]),
    ("packing", &["contact", "octree", "laws", "scene"]),
    ("run", &["contact", "octree", "laws", "scene", "packing"]),
    (
        "io",
        &["contact", "octree", "laws", "scene", "packing", "run"],
    ),
];

/// One source file: its module path and its code with comment lines removed.
struct Source {
    module: Vec<String>,
    file: String,
    code: String,
}

fn read_sources(dir: &Path, module: &[String], out: &mut Vec<Source>) {
    let mut entries: Vec<_> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let stem = path.file_stem().unwrap().to_string_lossy().to_string();
        if path.is_dir() {
            let mut sub = module.to_vec();
            sub.push(stem);
            read_sources(&path, &sub, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let mut m = module.to_vec();
            // A folder's mod.rs, the library's lib.rs and a binary's main.rs are the
            // folder's own module.
            if !matches!(stem.as_str(), "mod" | "lib" | "main") {
                m.push(stem);
            }
            let text = fs::read_to_string(&path).unwrap();
            let code = text
                .lines()
                .filter(|l| !l.trim_start().starts_with("//"))
                .collect::<Vec<_>>()
                .join("\n");
            out.push(Source {
                module: m,
                file: path.display().to_string(),
                code,
            });
        }
    }
}

/// The paths written from byte `start` of `s` on (`a::b::{c, d::{e, f}}` gives `a::b::c`,
/// `a::b::d::e`, `a::b::d::f`), and the byte where they end.
fn paths_at(s: &[u8], mut i: usize) -> (Vec<Vec<String>>, usize) {
    let mut prefix = Vec::new();
    loop {
        while i < s.len() && s[i].is_ascii_whitespace() {
            i += 1;
        }
        if i < s.len() && s[i] == b'{' {
            let mut all = Vec::new();
            i += 1;
            loop {
                while i < s.len() && (s[i].is_ascii_whitespace() || s[i] == b',') {
                    i += 1;
                }
                if i >= s.len() || s[i] == b'}' {
                    break;
                }
                let (inner, next) = paths_at(s, i);
                all.extend(inner.into_iter().map(|p| [prefix.clone(), p].concat()));
                i = next.max(i + 1);
            }
            return (all, i + 1);
        }
        let start = i;
        while i < s.len() && (s[i].is_ascii_alphanumeric() || s[i] == b'_') {
            i += 1;
        }
        if start == i {
            return (vec![prefix], i);
        }
        prefix.push(String::from_utf8_lossy(&s[start..i]).to_string());
        if s[i..].starts_with(b"::") {
            i += 2;
        } else {
            return (vec![prefix], i);
        }
    }
}

/// The inline modules (`mod tests { … }`) of a file: byte range and name.
fn inline_modules(code: &str) -> Vec<(usize, usize, String)> {
    let s = code.as_bytes();
    let mut out = Vec::new();
    for (at, _) in code.match_indices("mod ") {
        if at > 0 && !s[at - 1].is_ascii_whitespace() {
            continue;
        }
        let rest = &code[at + 4..];
        let name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if name.is_empty() || !rest[name.len()..].trim_start().starts_with('{') {
            continue;
        }
        let open = at + 4 + name.len() + rest[name.len()..].find('{').unwrap_or(0);
        let mut depth = 0usize;
        let mut end = s.len();
        for (k, &c) in s.iter().enumerate().skip(open) {
            match c {
                b'{' => depth += 1,
                b'}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = k;
                        break;
                    }
                }
                _ => {}
            }
        }
        out.push((open, end, name));
    }
    out
}

/// Every absolute module path the code names through `crate::` or `super::`.
fn referenced(src: &Source) -> Vec<Vec<String>> {
    let s = src.code.as_bytes();
    let inline = inline_modules(&src.code);
    let mut out = Vec::new();
    for (root, skip) in [("crate::", 0), ("super::", 1)] {
        for (at, _) in src.code.match_indices(root) {
            // Inside a longer path (`foo_crate::`, `super::super::`): read from its start.
            let before = &s[..at];
            if before
                .last()
                .is_some_and(|c| c.is_ascii_alphanumeric() || *c == b'_')
                || before.ends_with(b"::")
            {
                continue;
            }
            // `super` of a file's module; a later `super::` in the path climbs further.
            let (paths, _) = paths_at(s, at + root.len());
            for p in paths {
                let mut base: Vec<String> = if skip == 0 {
                    // A binary's `crate` is its own folder.
                    match src.module.first().map(String::as_str) {
                        Some("bin") => src.module[..2].to_vec(),
                        _ => Vec::new(),
                    }
                } else {
                    // The module the path is written in, inline modules included.
                    let mut here = src.module.clone();
                    here.extend(
                        inline
                            .iter()
                            .filter(|(a, b, _)| (*a..*b).contains(&at))
                            .map(|(_, _, n)| n.clone()),
                    );
                    here.pop();
                    here
                };
                let mut rest = p.as_slice();
                while rest.first().is_some_and(|x| x == "super") {
                    base.pop();
                    rest = &rest[1..];
                }
                base.extend(rest.iter().cloned());
                out.push(base);
            }
        }
    }
    out
}

#[test]
fn each_layer_imports_only_the_layers_below_it() {
    let mut sources = Vec::new();
    read_sources(Path::new("src"), &[], &mut sources);
    let allowed: BTreeMap<&str, &[&str]> = LAYERS.iter().copied().collect();
    let mut wrong = Vec::new();
    for src in sources
        .iter()
        .filter(|s| s.module.first().is_some_and(|m| m != "bin"))
    {
        let layer = src.module[0].as_str();
        let Some(ok) = allowed.get(layer) else {
            wrong.push(format!("{}: layer {layer} is not in LAYERS", src.file));
            continue;
        };
        for p in referenced(src) {
            let Some(target) = p.first() else { continue };
            if target != layer && !ok.contains(&target.as_str()) {
                wrong.push(format!("{}: {layer} imports {}", src.file, p.join("::")));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "imports against the layers:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn no_two_modules_of_a_folder_depend_on_each_other() {
    let mut sources = Vec::new();
    read_sources(Path::new("src"), &[], &mut sources);
    let modules: BTreeSet<Vec<String>> = sources.iter().map(|s| s.module.clone()).collect();
    // Names a folder's mod.rs re-exports, resolved to the child that defines them.
    let mut reexports: BTreeMap<(Vec<String>, String), String> = BTreeMap::new();
    for src in &sources {
        for stmt in src.code.split(';') {
            let t = stmt.trim_start();
            let Some(rest) = t
                .strip_prefix("pub use ")
                .or(t.strip_prefix("pub(crate) use "))
            else {
                continue;
            };
            let (paths, _) = paths_at(rest.as_bytes(), 0);
            for p in paths.iter().filter(|p| p.len() >= 2) {
                reexports.insert((src.module.clone(), p[p.len() - 1].clone()), p[0].clone());
            }
        }
    }
    // Edges child → child inside each folder.
    let mut edges: BTreeMap<Vec<String>, BTreeSet<(String, String)>> = BTreeMap::new();
    for src in &sources {
        for p in referenced(src) {
            for depth in 0..src.module.len().min(p.len()) {
                if src.module[..depth] != p[..depth] {
                    break;
                }
                let folder = src.module[..depth].to_vec();
                let from = &src.module[depth];
                let name = &p[depth];
                let child = if modules
                    .iter()
                    .any(|m| m.len() > depth && m[..depth] == folder[..] && &m[depth] == name)
                {
                    name.clone()
                } else if let Some(c) = reexports.get(&(folder.clone(), name.clone())) {
                    c.clone()
                } else {
                    continue;
                };
                if &child != from {
                    edges
                        .entry(folder)
                        .or_default()
                        .insert((from.clone(), child));
                }
            }
        }
    }
    let mut cycles = Vec::new();
    for (folder, e) in &edges {
        for (a, b) in e {
            // A path back from b to a closes a cycle.
            let mut seen = BTreeSet::from([b.clone()]);
            let mut stack = vec![b.clone()];
            while let Some(x) = stack.pop() {
                for (_, y) in e.iter().filter(|(f, _)| *f == x) {
                    if seen.insert(y.clone()) {
                        stack.push(y.clone());
                    }
                }
            }
            if seen.contains(a) {
                cycles.push(format!("{}: {a} → {b} → … → {a}", folder.join("::")));
            }
        }
    }
    assert!(cycles.is_empty(), "module cycles:\n{}", cycles.join("\n"));
}

#[test]
fn the_scan_sees_nested_groups_and_super_paths() {
    let src = Source {
        module: vec!["io".into(), "voxel".into(), "report".into()],
        file: "x".into(),
        code: "use crate::a::{b, c::{d, e}};\nuse super::moments::{f, g};\nlet x = super::super::h::i;\nmod tests {\n    use super::super::j;\n}".into(),
    };
    let got: Vec<String> = referenced(&src).iter().map(|p| p.join("::")).collect();
    assert_eq!(
        got,
        [
            "a::b",
            "a::c::d",
            "a::c::e",
            "io::voxel::moments::f",
            "io::voxel::moments::g",
            "io::h::i",
            "io::voxel::j"
        ]
    );
}

#[test]
fn every_unsafe_block_says_why_it_is_sound() {
    let mut sources = Vec::new();
    read_sources(Path::new("src"), &[], &mut sources);
    let mut bare = Vec::new();
    let mut count = 0;
    for src in &sources {
        let text = fs::read_to_string(&src.file).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        for (k, line) in lines.iter().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            if !(code.contains("unsafe {") || code.contains("unsafe fn")) {
                continue;
            }
            count += 1;
            // The comment lines right above the block (or its statement).
            let above = lines[..k]
                .iter()
                .rev()
                .take_while(|l| l.trim_start().starts_with("//"))
                .any(|l| l.contains("SAFETY:"));
            if !above {
                bare.push(format!("{}:{}", src.file, k + 1));
            }
        }
    }
    assert!(count > 0, "the scan found no unsafe code at all");
    assert!(
        bare.is_empty(),
        "unsafe without a SAFETY comment:\n{}",
        bare.join("\n")
    );
}
