//! The parameters of the packing loop a scene sets (`[packing]`).

/// Parameters of the packing loop, with defaults a user rarely changes
/// (`[packing]` in the scene file). The loop documents how it uses each.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PackingParams {
    /// Step limit: the loop stops with the reason "step limit" after this many FIRE
    /// steps in all. Default 100 000.
    pub max_steps: u64,
    /// When the target cannot be reached, the loop descends from its first jam (in
    /// steps of at least 0.9 of this), then bisects the scale between the best
    /// overlap-free one and the smallest jammed one until they are this close
    /// (relative). In `(0, 0.1]`; default 5 · 10⁻⁴ (0.15 % of packing fraction).
    pub jam_resolution: f64,
    /// Whether and how grains may turn while packing. Default [`Rotation::None`]:
    /// orientations stay as drawn, as the scene's statistics ask.
    pub rotation: Rotation,
    /// The most a grain may turn away from its drawn orientation, in radians, in
    /// `(0, π]`. Default π: no limit.
    pub max_turn: f64,
    /// Whether grains that may turn are turned back toward their drawn orientations,
    /// as far as their neighbours let them, once packed at the target. Default true.
    pub restore: bool,
    /// How much work the loop may spend when the target cannot be reached: below 1,
    /// each relaxation below the target may take `effort` times the default budget of
    /// steps before it counts as jammed; from 1.5 on, the jammed packing is compressed
    /// again and its jamming point searched anew `⌊2 (effort − 1)⌋` times, the
    /// densest kept (each 1–4 times the time at effort 1: equal spheres 1.2,
    /// lognormal ones with their swaps 3.9). Higher is denser and slower.
    /// In `[0.1, 100]`; default 1.
    pub effort: f64,
    /// Unjamming moves before each of effort's recompression cycles (so only with
    /// `effort` ≥ 1.5): see [`Unjam`]. Default [`Unjam::Swap`]: at next to no cost where
    /// there is nothing to swap, much denser where grains differ.
    pub unjam: Unjam,
    /// The smallest gap kept between grains, as a fraction of each pair's size: every
    /// pair keeps a Perram–Wertheim contact factor μ ≥ 1 + `gap` (the two grains, each
    /// scaled by 1 + `gap` about its centre, would at most touch), and every grain
    /// scaled by 1 + `gap` stays inside the walls of a walled box. Two spheres are then
    /// at least `gap · (r₁ + r₂)` apart, surface to surface. The loop packs the grains
    /// inflated by 1 + `gap`; every fraction it reports is of the grains themselves.
    /// At least 0; default 0.
    pub gap: f64,
    /// A time budget for the run before its outputs, in seconds (`packing.time_limit`):
    /// the drawing, the packing loop and its final check fit in it. With it,
    /// effort's recompression cycles go on, whatever `effort`, until the target is
    /// reached or the time is up, and the densest clean state is kept
    /// ([`StopReason::TimeLimit`](crate::packing::StopReason)). The outputs come on
    /// top. Positive; default none.
    pub time_limit: Option<f64>,
}

impl Default for PackingParams {
    fn default() -> Self {
        Self {
            max_steps: 100_000,
            jam_resolution: 5e-4,
            rotation: Rotation::None,
            max_turn: std::f64::consts::PI,
            restore: true,
            effort: 1.0,
            unjam: Unjam::Swap,
            gap: 0.0,
            time_limit: None,
        }
    }
}

/// How grains may turn while packing (`packing.rotation`). Turning lets a jammed
/// packing grow denser, at the price of orientations that are no longer the drawn ones:
/// the summary reports how far grains turned.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rotation {
    /// Orientations stay as drawn (`false`).
    None,
    /// Grains turn freely (`true`).
    Free,
    /// Grains of a tilt phase turn only about its tilt axis, so that their first axis
    /// stays in the plane the scene puts it in; other grains keep their orientation
    /// (`"axis"`).
    Axis,
}

impl Rotation {
    /// The value as `summary.json` names it.
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Free => "free",
            Self::Axis => "axis",
        }
    }
}

/// Unjamming moves between effort's recompression cycles (`packing.unjam`; the loop's
/// `unjam` module documents them).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unjam {
    /// None (`"none"`).
    None,
    /// Grains of similar volume swap positions where that lowers the overlap energy of
    /// the recompressed packing, each keeping its orientation (`"swap"`).
    Swap,
    /// The cycles anneal: hard-particle Monte Carlo (moves, turns, swaps) between
    /// small compressions, from below the jamming point (`"anneal"`).
    Anneal,
}

impl Unjam {
    /// Every value, as the scene file names it.
    pub const NAMES: [(&'static str, Self); 3] = [
        ("none", Self::None),
        ("swap", Self::Swap),
        ("anneal", Self::Anneal),
    ];

    /// The value as the scene file and `summary.json` name it.
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Swap => "swap",
            Self::Anneal => "anneal",
        }
    }
}
