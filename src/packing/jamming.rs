//! When a relaxation is jammed: the test that replaces a fixed ratio of energies per
//! window of steps.
//!
//! At a scale above jamming, an energy minimisation converges to a state of positive
//! energy (O'Hern et al., *Phys. Rev. E* 68, 011306, 2003: jammed states have positive
//! energy and pressure that vanish at the jamming point); below it, the energy goes to
//! zero, often slowly and in bursts near jamming, in mixtures of very different sizes
//! and for slender grains. A relaxation is declared jammed when **both**
//! 1. the energy per grain has converged to a **plateau**: its log-log slope
//!    `−d ln E / d ln t`, measured on the least energy of each window of steps over
//!    the latest doubling of the steps, has fallen below
//!    [`FireParams::plateau_slope`] **and** is no steeper than over the doubling
//!    before (the decrease rate goes to zero). A power law `t^−a` with
//!    `a > plateau_slope` keeps the relaxation going however slow it is per step, and
//!    so does an exponential decay `e^(−t/τ)`, however long τ, since its log-log
//!    slope `t/τ` rises; a plateau is recognised after about twice the steps it took
//!    to reach it;
//! 2. that plateau is **positive**: above `PLATEAU_FLOOR` times the energy per grain
//!    of a state whose every grain has one contact overlapping by the margin — below
//!    it the state is one breath from clean, and the relaxation goes on.
//!
//! A relaxation may also be given a **patience** (the loop gives one to its first
//! relaxations, from random positions, see `QUENCH_STEP` in `packing/effort.rs`):
//! still not clean after that many steps and **shallow** (energy per grain below
//! [`DEEP`] times the margin's), it is jammed. Just above its jamming point a
//! relaxation from random positions creeps without end: 10 000 equal spheres at 0.66
//! from 1.6e-3 to 1.02e-3 per grain (400 to 255 times the margin's energy) between
//! steps 500 and 4 000, where the plateau test called it; 10 000 lognormal spheres at
//! 0.657 fell below the floor and crept on for the target's whole budget of 20 000
//! steps (BENCHMARKS.md, "issue 27"). A deep relaxation, far above its jamming point,
//! settles on its plateau in about a thousand steps and is left to.
//!
//! Judged no earlier than after [`MIN_WINDOWS`] windows, so that FIRE's start (its step
//! grows for a few hundred steps) is never taken for a plateau.
//!
//! [`FireParams::plateau_slope`]: super::FireParams::plateau_slope

/// Fewest windows before a relaxation may be judged jammed: FIRE's time step takes
/// about `ln(dt_max/dt_start)/ln(dt_grow) + n_delay ≈ 27` steps of positive power to
/// grow, and often several restarts; 4 windows of 100 steps leave room for both.
pub(crate) const MIN_WINDOWS: usize = 4;

/// How far above the energy of "one contact per grain overlapping by the margin" a
/// plateau must be to count as jammed (see the module docs). 4: a jammed state has
/// about 3 overlapping contacts per grain (6 per grain shared by two) at the very
/// least, each well above the margin.
pub(crate) const PLATEAU_FLOOR: f64 = 4.0;

/// Below [`PLATEAU_FLOOR`], a plateau still counts as jammed when every window of the
/// latest doubling kept a pair overlapping, at the relaxation's own scale, by more than
/// `NEAR_CLEAN` times the bisection's resolution (`packing.jam_resolution`), relative
/// to the scale. Such a state is not one breath from clean: its energy has stopped
/// falling while an overlap of a sizeable share of the resolution persists. A state
/// converging to one that is clean by a hair has its largest overlap shrinking toward
/// zero and goes on. Measured on 10 000 equal spheres (BENCHMARKS.md, "third round"):
/// the trials next to the jamming point plateau at a tenth of the floor from their
/// first windows, with an overlap of 0.7 of the resolution, and used to run out of
/// their budget.
pub(crate) const NEAR_CLEAN: f64 = 0.25;

/// The energy per grain, in units of the margin's (one contact per grain overlapping
/// by the margin), from which a relaxation is **deep**: far enough above its jamming
/// point that it settles on its plateau in about a thousand steps, and that the search
/// from the state it leaves finds a dense jamming point. Below it, a relaxation with a
/// patience is cut at its patience (module docs), and the loop compresses the state
/// further (`packing/effort.rs`, `QUENCH_STEP`). 1000: 10 000 equal spheres from
/// random positions settle at 2 050 at 0.70 (the search from there reaches 0.6418)
/// and creep at 400–255 at 0.66 (the search from there reached 0.6390 after 5 500
/// steps); BENCHMARKS.md, "issue 27".
pub(crate) const DEEP: f64 = 1000.0;

/// Before its full patience, a shallow relaxation is cut only while it creeps: while
/// its energy falls slower than `1/t` over the latest doubling of the steps
/// (−d ln E / d ln t below `CREEP`). The creep just above jamming falls as `t^−0.3` to
/// `t^−0.1`; a relaxation on its way to clean falls faster than any power, and is left
/// to its full patience: with a patience shorter than its clearing time (`effort`
/// below 1), 10 000 equal spheres asked for 0.62, clean after 612 steps, were
/// otherwise cut at 100 and took 1 369 (BENCHMARKS.md, issue 27, second round).
pub(crate) const CREEP: f64 = 1.0;

/// When a shallow relaxation counts as jammed (module docs): from `creeping` steps on
/// while it creeps ([`CREEP`]), from `any` steps on whatever its slope; and from
/// `deep` steps on, a deep one too, plateau or not (the loop gives one below
/// `effort = 1`: see `DEEP_PATIENCE` in `packing/effort.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Patience {
    pub creeping: u64,
    pub any: u64,
    pub deep: u64,
}

impl Patience {
    /// No patience: a relaxation runs to its plateau or its budget.
    pub const NONE: Self = Self::of(u64::MAX);

    /// The same patience for shallow relaxations whatever the slope; deep ones run to
    /// their plateau.
    pub const fn of(steps: u64) -> Self {
        Self {
            creeping: steps,
            any: steps,
            deep: u64::MAX,
        }
    }
}

/// What the test says after a window.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Verdict {
    /// Not (yet) jammed: go on relaxing.
    Relaxing,
    /// The energy per grain has converged to a positive plateau.
    Jammed,
}

/// The jamming test of one relaxation: fed the energy of every step, judged once per
/// window.
#[derive(Debug, Clone)]
pub(crate) struct JamTest {
    window: u64,
    slope: f64,
    /// Energy per grain below which a plateau does not count.
    floor: f64,
    /// Energy per grain from which a relaxation is deep ([`DEEP`]).
    deep: f64,
    /// When a shallow relaxation is jammed (module docs).
    patience: Patience,
    /// The least energy per grain of each finished window.
    minima: Vec<f64>,
    current: f64,
    /// Overlap (relative to the scale) below which a plateau under the floor goes on.
    near_clean: f64,
    /// The least largest overlap of each finished window, and of the current one.
    overlaps: Vec<f64>,
    current_overlap: f64,
    steps: u64,
}

impl JamTest {
    /// A test judged every `window` steps with plateau slope `slope`, for grains whose
    /// contacts overlapping by the margin have energy `margin_energy` each (per grain).
    /// `resolution` is the bisection's relative resolution (see [`NEAR_CLEAN`]);
    /// `patience` when a shallow relaxation is jammed.
    pub fn new(
        window: u64,
        slope: f64,
        margin_energy: f64,
        resolution: f64,
        patience: Patience,
    ) -> Self {
        Self {
            window,
            slope,
            floor: PLATEAU_FLOOR * margin_energy,
            deep: DEEP * margin_energy,
            patience,
            minima: Vec::new(),
            current: f64::INFINITY,
            near_clean: NEAR_CLEAN * resolution,
            overlaps: Vec::new(),
            current_overlap: f64::INFINITY,
            steps: 0,
        }
    }

    /// Takes one step's energy per grain and its largest pair overlap at the
    /// relaxation's scale, relative to the scale (`1 − μ_min / s`, 0 for none); at
    /// the end of a window, judges.
    pub fn step(&mut self, energy_per_grain: f64, overlap: f64) -> Verdict {
        self.current = self.current.min(energy_per_grain);
        self.current_overlap = self.current_overlap.min(overlap);
        self.steps += 1;
        if !self.steps.is_multiple_of(self.window) {
            return Verdict::Relaxing;
        }
        self.minima
            .push(std::mem::replace(&mut self.current, f64::INFINITY));
        self.overlaps
            .push(std::mem::replace(&mut self.current_overlap, f64::INFINITY));
        let k = self.minima.len();
        if k < MIN_WINDOWS {
            return Verdict::Relaxing;
        }
        // −d ln E / d ln t over the latest doubling of the steps, and over the one
        // before: windows (k−1)/4 → (k−1)/2 → k−1, which end at (i+1)·W steps.
        let (early, mid, now) = ((k - 1) / 4, (k - 1) / 2, k - 1);
        let slope = |a: usize, b: usize| {
            (self.minima[a] / self.minima[b]).ln() / ((b + 1) as f64 / (a + 1) as f64).ln()
        };
        let (latest, before) = (slope(mid, now), slope(early, mid));
        let energy = self.minima[now];
        let plateau = energy > 0.0 && latest < self.slope && latest <= before;
        let overlapping = || self.overlaps[mid..].iter().all(|&o| o > self.near_clean);
        let out_of_patience = if self.is_deep(energy) {
            self.steps >= self.patience.deep
        } else {
            self.steps >= self.patience.any
                || (self.steps >= self.patience.creeping && latest < CREEP)
        };
        if (plateau && (energy > self.floor || overlapping())) || out_of_patience {
            Verdict::Jammed
        } else {
            Verdict::Relaxing
        }
    }

    /// Whether a relaxation at `energy_per_grain` is deep ([`DEEP`]).
    pub fn is_deep(&self, energy_per_grain: f64) -> bool {
        energy_per_grain >= self.deep
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const WINDOW: u64 = 100;
    const SLOPE: f64 = 0.1;
    const RESOLUTION: f64 = 1e-3;

    /// The step at which the test says jammed for the energy `e(t)`, if it does
    /// within `steps`.
    fn jammed_at(e: impl Fn(f64) -> f64, steps: u64, margin_energy: f64) -> Option<u64> {
        jammed_overlapping(e, |_| 0.0, steps, margin_energy)
    }

    /// As [`jammed_at`], with the largest overlap `o(t)` (relative, resolution 1e-3).
    fn jammed_overlapping(
        e: impl Fn(f64) -> f64,
        o: impl Fn(f64) -> f64,
        steps: u64,
        margin_energy: f64,
    ) -> Option<u64> {
        let mut test = JamTest::new(WINDOW, SLOPE, margin_energy, RESOLUTION, Patience::NONE);
        (1..=steps).find(|&t| test.step(e(t as f64), o(t as f64)) == Verdict::Jammed)
    }

    /// An energy decaying to zero, exponentially or as a power law steeper than the
    /// plateau slope, is never called jammed, however slowly it falls per step: the
    /// window test it replaces (20 % per 100 steps) called a decay `t^−0.5` stuck
    /// after 200 steps.
    #[test]
    fn decay_toward_zero_is_not_jammed() {
        assert_eq!(jammed_at(|t| (-t / 3000.0).exp(), 100_000, 1e-30), None);
        assert_eq!(jammed_at(|t| t.powf(-0.5), 100_000, 1e-30), None);
        assert_eq!(jammed_at(|t| t.powf(-0.2), 100_000, 1e-30), None);
    }

    /// The recompression cycles judge with half the window (`CYCLE_WINDOW` in
    /// `packing/effort.rs`): decays to zero still go on, a plateau is still recognised.
    #[test]
    fn half_window_lets_decays_run_and_finds_plateaus() {
        let half = |e: &dyn Fn(f64) -> f64, steps: u64| {
            let mut test = JamTest::new(WINDOW / 2, SLOPE, 1e-30, RESOLUTION, Patience::NONE);
            (1..=steps).find(|&t| test.step(e(t as f64), 0.0) == Verdict::Jammed)
        };
        assert_eq!(half(&|t| (-t / 3000.0).exp(), 100_000), None);
        assert_eq!(half(&|t| t.powf(-0.2), 100_000), None);
        assert_eq!(
            half(&|_| 1.0, 10_000),
            Some(WINDOW / 2 * MIN_WINDOWS as u64)
        );
    }

    /// Slow decays in bursts (a plateau, then a drop, as rattlers escape near
    /// jamming) are not cut short while each plateau is shorter than half the steps
    /// before it: here the energy halves at steps 100 · 1.5^k.
    #[test]
    fn bursts_are_not_cut_short() {
        let bursts = |t: f64| 0.5f64.powi(((t / 100.0).ln() / 1.5f64.ln()).floor() as i32);
        assert_eq!(jammed_at(bursts, 50_000, 1e-30), None);
    }

    /// With a patience, a relaxation still shallow then is jammed at the first window
    /// end from it (the creep of 10 000 equal spheres at 0.66, module docs, and a decay
    /// below the floor); a deep one goes on to its plateau, and one clean before
    /// its patience never meets it.
    #[test]
    fn a_shallow_relaxation_is_jammed_at_its_patience() {
        let patience = |e: &dyn Fn(f64) -> f64, margin_energy: f64| {
            let mut test =
                JamTest::new(WINDOW, SLOPE, margin_energy, RESOLUTION, Patience::of(1000));
            (1..=100_000u64).find(|&t| test.step(e(t as f64), 0.0) == Verdict::Jammed)
        };
        let creep = |t: f64| 1.6e-3 * (t / 500.0).powf(-0.25);
        assert_eq!(patience(&creep, 4e-6), Some(1000));
        assert_eq!(
            patience(&|t| 1e-5 * (t / 500.0).powf(-0.25), 4e-6),
            Some(1000)
        );
        // Ten times deeper (4 000 margin energies), the creep goes on to a plateau.
        let settling = |t: f64| 1.6e-2 * (1.0 + (t / 500.0).powf(-0.25) * (-t / 2000.0).exp());
        let deep = patience(&settling, 4e-6).expect("a plateau");
        assert!(deep > 2000, "{deep}");
        // Without a patience, the shallow creep runs on.
        assert_eq!(jammed_at(creep, 20_000, 4e-6), None);
        // A shallow relaxation on its way to clean (falling faster than any power) is
        // not cut at a patience shorter than its clearing time ([`CREEP`]).
        let clearing = |t: f64| 1e-3 * (-t / 150.0).exp();
        let patience = Patience {
            creeping: 100,
            any: 1000,
            deep: u64::MAX,
        };
        let mut test = JamTest::new(WINDOW, SLOPE, 4e-6, RESOLUTION, patience);
        assert!((1..=600u64).all(|t| test.step(clearing(t as f64), 0.0) == Verdict::Relaxing));
    }

    /// With a deep patience (below `effort = 1`), a deep relaxation still settling is
    /// jammed at the first window end from it; a shallow one keeps its own patience.
    #[test]
    fn a_deep_relaxation_is_jammed_at_its_deep_patience() {
        let patience = Patience {
            creeping: 100,
            any: 1000,
            deep: 300,
        };
        let first = |e: &dyn Fn(f64) -> f64| {
            let mut test = JamTest::new(WINDOW, SLOPE, 4e-6, RESOLUTION, patience);
            (1..=100_000u64).find(|&t| test.step(e(t as f64), 0.0) == Verdict::Jammed)
        };
        // 4 000 margin energies and still falling: a plateau only after 2 000 steps.
        let settling = |t: f64| 1.6e-2 * (1.0 + (t / 500.0).powf(-0.25) * (-t / 2000.0).exp());
        // Judged from MIN_WINDOWS windows on, as every relaxation.
        assert_eq!(first(&settling), Some(WINDOW * MIN_WINDOWS as u64));
        // A shallow creep is cut at its creeping patience's first judged window.
        let creep = |t: f64| 1.6e-3 * (t / 500.0).powf(-0.25);
        assert_eq!(first(&creep), Some(WINDOW * MIN_WINDOWS as u64));
        // Without it, the deep one goes on to its plateau.
        let mut test = JamTest::new(WINDOW, SLOPE, 4e-6, RESOLUTION, Patience::of(1000));
        let plateau =
            (1..=100_000u64).find(|&t| test.step(settling(t as f64), 0.0) == Verdict::Jammed);
        assert!(plateau.is_some_and(|t| t > 2000), "{plateau:?}");
    }

    /// An energy converging to a positive plateau is jammed soon after it settles, not
    /// before.
    #[test]
    fn positive_plateau_is_jammed() {
        let settle = 2000.0;
        let e = |t: f64| 1e-3 * (1.0 + (-t / (settle / 10.0)).exp() * 100.0);
        let at = jammed_at(e, 100_000, 1e-9).expect("jammed");
        assert!(at >= 2 * WINDOW * MIN_WINDOWS as u64 / 2, "{at}");
        assert!(at <= 4 * settle as u64, "{at}");
        // A constant from the start is judged after MIN_WINDOWS windows.
        assert_eq!(
            jammed_at(|_| 1.0, 10_000, 1e-9),
            Some(WINDOW * MIN_WINDOWS as u64)
        );
    }

    /// A plateau at the margin's own energy is no jam: the state is almost clean.
    #[test]
    fn plateau_below_the_floor_is_not_jammed() {
        assert_eq!(jammed_at(|_| 2.0e-9, 10_000, 1e-9), None);
        assert!(jammed_at(|_| 5.0e-9, 10_000, 1e-9).is_some());
    }

    /// Below the floor, a plateau whose largest overlap stays above the near-clean
    /// share of the resolution is jammed; one whose overlap shrinks toward zero (a
    /// state converging to one clean by a hair) goes on, as does one that dips below
    /// that share in any window of the latest doubling.
    #[test]
    fn plateau_below_the_floor_with_a_lasting_overlap_is_jammed() {
        let flat = |_: f64| 2.0e-9;
        let lasting = |_: f64| 0.7 * RESOLUTION;
        assert_eq!(
            jammed_overlapping(flat, lasting, 10_000, 1e-9),
            Some(WINDOW * MIN_WINDOWS as u64)
        );
        let closing = |t: f64| 0.7 * RESOLUTION * (-t / 300.0).exp();
        assert_eq!(jammed_overlapping(flat, closing, 10_000, 1e-9), None);
        let dipping = |t: f64| {
            if (t as u64 / WINDOW) % 3 == 2 {
                0.1 * RESOLUTION
            } else {
                RESOLUTION
            }
        };
        assert_eq!(jammed_overlapping(flat, dipping, 10_000, 1e-9), None);
    }
}
