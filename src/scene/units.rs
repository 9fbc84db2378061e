//! The scene's units (`[units]`): what its lengths and stresses are in, and how each
//! writer converts them to what its program expects.
//!
//! A scene's numbers are in its own units everywhere it is read and packed; only the
//! writers convert: DAMASK's `material.yaml` and `rve.vti` go out in SI (Pa, m), the
//! Abaqus/CalculiX decks, the VTK files and the CSV tables in the scene's units.
//!
//! ```
//! use grainpack::scene::{LengthUnit, StressUnit, Units};
//! let units = Units::default();
//! assert_eq!((units.length, units.stress), (LengthUnit::Micrometre, StressUnit::Megapascal));
//! assert_eq!(units.length.to_si(40.0), 40e-6);
//! assert_eq!(units.stress.to_si(70000.0), 70e9);
//! assert_eq!(units.stress.from_si(200e9), 200000.0);
//! ```

/// A unit of length.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LengthUnit {
    /// `"m"`.
    Metre,
    /// `"mm"`.
    Millimetre,
    /// `"um"` (also `"µm"`, `"μm"`).
    Micrometre,
    /// `"nm"`.
    Nanometre,
}

/// A unit of stress (and of elastic moduli).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StressUnit {
    /// `"Pa"`.
    Pascal,
    /// `"kPa"`.
    Kilopascal,
    /// `"MPa"` (N/mm²).
    Megapascal,
    /// `"GPa"`.
    Gigapascal,
}

/// The units a scene states once (`[units]`): every length (box, grain sizes, voxel
/// size, measured tables) in `length`, every stress and modulus (`[phase.elastic]`,
/// `[matrix.elastic]`) in `stress`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Units {
    /// Unit of every length of the scene.
    pub length: LengthUnit,
    /// Unit of every stress and elastic modulus of the scene.
    pub stress: StressUnit,
}

impl Default for Units {
    /// Micrometres and megapascals, what microstructures and moduli are usually given
    /// in.
    fn default() -> Self {
        Self {
            length: LengthUnit::Micrometre,
            stress: StressUnit::Megapascal,
        }
    }
}

impl LengthUnit {
    /// Every accepted spelling, with its unit (`docs/config.md` lists them).
    pub const NAMES: [(&'static str, LengthUnit); 6] = [
        ("m", LengthUnit::Metre),
        ("mm", LengthUnit::Millimetre),
        ("um", LengthUnit::Micrometre),
        ("µm", LengthUnit::Micrometre),
        ("μm", LengthUnit::Micrometre),
        ("nm", LengthUnit::Nanometre),
    ];

    /// The unit's name as `summary.json` and the deck's header write it (ASCII).
    pub fn symbol(self) -> &'static str {
        match self {
            LengthUnit::Metre => "m",
            LengthUnit::Millimetre => "mm",
            LengthUnit::Micrometre => "um",
            LengthUnit::Nanometre => "nm",
        }
    }

    /// Units per metre, a power of ten and so an exact double: dividing by it rounds
    /// once, to the double nearest the decimal (`40 µm` gives the same `4e-5` as
    /// written in metres).
    fn per_metre(self) -> f64 {
        match self {
            LengthUnit::Metre => 1.0,
            LengthUnit::Millimetre => 1e3,
            LengthUnit::Micrometre => 1e6,
            LengthUnit::Nanometre => 1e9,
        }
    }

    /// `value` (in this unit) in metres.
    pub fn to_si(self, value: f64) -> f64 {
        value / self.per_metre()
    }

    /// `value` (in metres) in this unit.
    pub fn from_si(self, value: f64) -> f64 {
        value * self.per_metre()
    }
}

impl StressUnit {
    /// Every accepted spelling, with its unit (case matters: `mPa` is not `MPa`).
    pub const NAMES: [(&'static str, StressUnit); 4] = [
        ("Pa", StressUnit::Pascal),
        ("kPa", StressUnit::Kilopascal),
        ("MPa", StressUnit::Megapascal),
        ("GPa", StressUnit::Gigapascal),
    ];

    /// The unit's name as written in the scene.
    pub fn symbol(self) -> &'static str {
        match self {
            StressUnit::Pascal => "Pa",
            StressUnit::Kilopascal => "kPa",
            StressUnit::Megapascal => "MPa",
            StressUnit::Gigapascal => "GPa",
        }
    }

    /// Pascals per unit, a power of ten and so an exact double (one rounding per
    /// conversion).
    fn pascals(self) -> f64 {
        match self {
            StressUnit::Pascal => 1.0,
            StressUnit::Kilopascal => 1e3,
            StressUnit::Megapascal => 1e6,
            StressUnit::Gigapascal => 1e9,
        }
    }

    /// `value` (in this unit) in pascals.
    pub fn to_si(self, value: f64) -> f64 {
        value * self.pascals()
    }

    /// `value` (in pascals) in this unit.
    pub fn from_si(self, value: f64) -> f64 {
        value / self.pascals()
    }
}

/// The box sides (in metres) a scene is expected to have: from 1 nm (a few atoms) to
/// 10 m (a large RVE of aggregates). A side outside is allowed, with a warning naming
/// `box.size`: it is more likely a length in the wrong unit.
pub const PLAUSIBLE_BOX_M: (f64, f64) = (1e-9, 10.0);

/// The elastic moduli (Young's, and the stiffness constants of a DAMASK phase, in
/// pascals) a solid is expected to have: from 1 kPa (the softest gels) to 2 TPa (twice
/// diamond's 1.05 TPa). A modulus outside is allowed, with a warning naming its key:
/// `E = 200` in `"Pa"` is more likely GPa.
pub const PLAUSIBLE_MODULUS_PA: (f64, f64) = (1e3, 2e12);

/// The diagonal stiffness constants (`C_11`, `C_44`, …, in pascals) a crystal is
/// expected to have, which DAMASK's phases are: from 0.1 GPa, ten times below the
/// softest of the elements (caesium, C_44 ≈ 1.5 GPa), to 2 TPa (diamond's C_11 is
/// 1.08 TPa). A constant outside is allowed, with a warning naming its key: a
/// `[phase.damask]` table is in pascals whatever `[units]` says, and `C_11 = 250000`
/// is more likely MPa.
pub const PLAUSIBLE_CRYSTAL_STIFFNESS_PA: (f64, f64) = (1e8, 2e12);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions_to_si_round_once_and_invert() {
        // Division by an exact power of ten: the double nearest the decimal.
        assert_eq!(LengthUnit::Micrometre.to_si(40.0), 4e-5);
        assert_eq!(LengthUnit::Millimetre.to_si(12.5), 0.0125);
        assert_eq!(LengthUnit::Nanometre.to_si(3.0), 3e-9);
        assert_eq!(LengthUnit::Metre.to_si(0.7), 0.7);
        assert_eq!(StressUnit::Gigapascal.to_si(210.0), 210e9);
        assert_eq!(StressUnit::Kilopascal.to_si(5.0), 5e3);
        assert_eq!(StressUnit::Megapascal.from_si(70e9), 70000.0);
        for (_, unit) in LengthUnit::NAMES {
            assert_eq!(unit.from_si(unit.to_si(40.0)), 40.0);
        }
        for (_, unit) in StressUnit::NAMES {
            assert_eq!(unit.from_si(unit.to_si(400000.0)), 400000.0);
        }
    }

    #[test]
    fn every_unit_has_a_name_that_reads_back() {
        for (name, unit) in LengthUnit::NAMES {
            let back = LengthUnit::NAMES.iter().find(|(n, _)| *n == unit.symbol());
            assert_eq!(back.map(|b| b.1), Some(unit), "{name}");
        }
        for (_, unit) in StressUnit::NAMES {
            let back = StressUnit::NAMES.iter().find(|(n, _)| *n == unit.symbol());
            assert_eq!(back.map(|b| b.1), Some(unit));
        }
    }
}
