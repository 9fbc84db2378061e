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
    /// The least energy per grain of each finished window.
    minima: Vec<f64>,
    current: f64,
    steps: u64,
}

impl JamTest {
    /// A test judged every `window` steps with plateau slope `slope`, for grains whose
    /// contacts overlapping by the margin have energy `margin_energy` each (per grain).
    pub fn new(window: u64, slope: f64, margin_energy: f64) -> Self {
        Self {
            window,
            slope,
            floor: PLATEAU_FLOOR * margin_energy,
            minima: Vec::new(),
            current: f64::INFINITY,
            steps: 0,
        }
    }

    /// Takes one step's energy per grain; at the end of a window, judges.
    pub fn step(&mut self, energy_per_grain: f64) -> Verdict {
        self.current = self.current.min(energy_per_grain);
        self.steps += 1;
        if !self.steps.is_multiple_of(self.window) {
            return Verdict::Relaxing;
        }
        self.minima
            .push(std::mem::replace(&mut self.current, f64::INFINITY));
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
        if plateau && energy > self.floor {
            Verdict::Jammed
        } else {
            Verdict::Relaxing
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const WINDOW: u64 = 100;
    const SLOPE: f64 = 0.1;

    /// The step at which the test says jammed for the energy `e(t)`, if it does
    /// within `steps`.
    fn jammed_at(e: impl Fn(f64) -> f64, steps: u64, margin_energy: f64) -> Option<u64> {
        let mut test = JamTest::new(WINDOW, SLOPE, margin_energy);
        (1..=steps).find(|&t| test.step(e(t as f64)) == Verdict::Jammed)
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

    /// Slow decays in bursts (a plateau, then a drop, as rattlers escape near
    /// jamming) are not cut short while each plateau is shorter than half the steps
    /// before it: here the energy halves at steps 100 · 1.5^k.
    #[test]
    fn bursts_are_not_cut_short() {
        let bursts = |t: f64| 0.5f64.powi(((t / 100.0).ln() / 1.5f64.ln()).floor() as i32);
        assert_eq!(jammed_at(bursts, 50_000, 1e-30), None);
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
}
