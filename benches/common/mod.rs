//! What the benchmarks share: the machine line and the rewriting of BENCHMARKS.md.

/// CPU, cores, date and load average, for the record.
pub fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let date = std::process::Command::new("date")
        .args(["-u", "+%F"])
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default();
    let load = std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_default();
    format!("{cpu}, {cores} cores; {date}; load average at start {load} (shared machine: other jobs inflate times)")
}

/// Replaces the text between `<!-- NAME:begin -->` and `<!-- NAME:end -->` in `path`
/// (written to a temporary file and renamed), or appends the block if the markers are
/// missing.
pub fn update_section(path: &str, name: &str, text: &str) {
    let (begin, end) = (
        format!("<!-- {name}:begin -->"),
        format!("<!-- {name}:end -->"),
    );
    let old = std::fs::read_to_string(path).unwrap_or_else(|_| "# Benchmarks\n".into());
    let block = format!("{begin}\n{text}{end}");
    let new = match (old.find(&begin), old.find(&end)) {
        (Some(b), Some(e)) if b < e => format!("{}{block}{}", &old[..b], &old[e + end.len()..]),
        _ => format!("{old}\n{block}\n"),
    };
    let tmp = format!("{path}.tmp");
    std::fs::write(&tmp, new).unwrap();
    std::fs::rename(tmp, path).unwrap();
}

/// Draws a scene's grains with its seed and packs them: the packing, the number of
/// grains and the seconds `pack` took (its final exact check included).
#[allow(dead_code)] // not every bench packs
pub fn pack_scene(
    scene: &grainpack::scene::Scene,
) -> (
    grainpack::packing::Packing,
    Vec<grainpack::scene::GrainSpec>,
    f64,
) {
    let specs = scene.sample_grains(&mut scene.rng()).unwrap();
    let t = std::time::Instant::now();
    let job = grainpack::packing::Job {
        specs: &specs,
        domain: &scene.domain,
        params: &scene.packing,
        tuning: &grainpack::packing::Tuning::default(),
        seed: scene.seed,
    };
    let p = grainpack::packing::pack(
        &job,
        &std::sync::atomic::AtomicBool::new(false),
        &mut |_| {},
    )
    .unwrap();
    let secs = t.elapsed().as_secs_f64();
    (p, specs, secs)
}
