//! The scene file as written: a serde mirror that rejects unknown keys and keeps the
//! span of every value for error messages. Only `validate` reads it.

use serde::Deserialize;
use toml::Spanned;

/// Optional spanned value.
type Opt<T> = Option<Spanned<T>>;

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawScene {
    pub seed: Opt<u64>,
    #[serde(rename = "box")]
    pub domain: Spanned<RawBox>,
    pub grains: Opt<u64>,
    pub target_fraction: Opt<f64>,
    #[serde(default)]
    pub phase: Vec<Spanned<RawPhase>>,
    pub packing: Opt<RawPacking>,
    pub output: Opt<RawOutput>,
    pub matrix: Opt<RawMatrix>,
    /// `[homogenization]`: checked by validation, passed through to `material.yaml`.
    pub homogenization: Opt<toml::Table>,
    pub units: Opt<RawUnits>,
}

/// `[units]`: the names, checked by validation.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawUnits {
    pub length: Opt<String>,
    pub stress: Opt<String>,
}

/// `[matrix]`: the matrix material of `rve_fill = "matrix"`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMatrix {
    pub elastic: Opt<RawElastic>,
    pub damask: Opt<toml::Table>,
}

/// `[phase.elastic]`, `[matrix.elastic]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawElastic {
    #[serde(rename = "E")]
    pub young: Spanned<f64>,
    pub nu: Spanned<f64>,
}

/// `[phase.texture]`: every kind's keys, each optional.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawTexture {
    pub kind: Spanned<RawTextureKind>,
    pub quaternion: Opt<[f64; 4]>,
    pub euler: Opt<[f64; 3]>,
    pub crystal_direction: Opt<[f64; 3]>,
    /// `"x"`, `"y"`, `"z"` or `[x, y, z]`: checked by validation.
    pub sample_direction: Opt<toml::Value>,
    pub kappa: Opt<f64>,
    pub file: Opt<String>,
    pub relative_to_shape: Opt<bool>,
}

/// `texture.kind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum RawTextureKind {
    Random,
    Fixed,
    Fibre,
    File,
}

/// `[box]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawBox {
    /// `[Lx, Ly, Lz]`, or `[Lx, Ly]` for a 2D scene: the count is checked by validation.
    pub size: Spanned<Vec<f64>>,
    pub boundary: Opt<RawBoundary>,
}

/// `box.boundary`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum RawBoundary {
    Periodic,
    Reflecting,
}

/// One `[[phase]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawPhase {
    pub name: Opt<String>,
    pub share: Opt<f64>,
    /// Required unless `measured` gives the grains.
    pub size: Opt<RawDistribution>,
    pub aspect_ratio: Opt<RawDistribution>,
    pub b_over_a: Opt<RawDistribution>,
    pub c_over_a: Opt<RawDistribution>,
    pub c_over_b: Opt<RawDistribution>,
    pub orientation: Opt<RawOrientation>,
    pub texture: Opt<RawTexture>,
    pub elastic: Opt<RawElastic>,
    pub damask: Opt<toml::Table>,
    pub measured: Opt<RawMeasured>,
}

/// `[phase.measured]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMeasured {
    pub file: Spanned<String>,
    pub mode: Opt<String>,
    /// An index or a name: checked by validation.
    pub phase: Opt<toml::Value>,
}

/// `[phase.size]` and `[phase.aspect_ratio]`: every family's keys, each optional;
/// validation rejects the keys that do not belong to the chosen family.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawDistribution {
    pub distribution: Spanned<RawFamily>,
    pub value: Opt<f64>,
    pub mean: Opt<f64>,
    pub std: Opt<f64>,
    pub sigma: Opt<f64>,
    pub scale: Opt<f64>,
    pub loc: Opt<f64>,
    pub min: Opt<f64>,
    pub max: Opt<f64>,
    /// `distribution = "table"`: points, fractions, basis, interpolation.
    pub x: Opt<Vec<f64>>,
    pub cdf: Opt<Vec<f64>>,
    pub by: Opt<String>,
    pub interpolation: Opt<String>,
}

impl RawDistribution {
    /// Every parameter key with its value, in the order of the docs.
    pub fn params(&self) -> [(&'static str, Option<&Spanned<f64>>); 8] {
        [
            ("value", self.value.as_ref()),
            ("mean", self.mean.as_ref()),
            ("std", self.std.as_ref()),
            ("sigma", self.sigma.as_ref()),
            ("scale", self.scale.as_ref()),
            ("loc", self.loc.as_ref()),
            ("min", self.min.as_ref()),
            ("max", self.max.as_ref()),
        ]
    }

    /// The parameter called `name`, if given.
    pub fn param(&self, name: &str) -> Option<&Spanned<f64>> {
        self.params()
            .into_iter()
            .find(|(n, _)| *n == name)
            .and_then(|(_, v)| v)
    }
}

/// `distribution = "..."`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum RawFamily {
    Constant,
    Uniform,
    Normal,
    LogNormal,
    Table,
}

/// `[phase.orientation]`: every kind's keys, each optional.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawOrientation {
    pub kind: Spanned<RawKind>,
    pub quaternion: Opt<[f64; 4]>,
    /// `"x"`, `"y"`, `"z"` or `[x, y, z]`: checked by validation.
    pub axis: Opt<toml::Value>,
    pub mean: Opt<f64>,
    pub kappa: Opt<f64>,
    pub min: Opt<f64>,
    pub max: Opt<f64>,
    /// `kind = "fisher"`: `"x"`, `"y"`, `"z"` or `[x, y, z]`.
    pub direction: Opt<toml::Value>,
    pub spin_reference: Opt<toml::Value>,
    pub spin_kappa: Opt<f64>,
    pub spin_mean: Opt<f64>,
    /// `kind = "aligned"` in a 2D scene: the grains' angle from x, in degrees.
    pub angle: Opt<f64>,
}

/// `orientation.kind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum RawKind {
    Random,
    Fixed,
    Aligned,
    Tilt,
    Fisher,
    /// 2D scenes: a von Mises law of the angle (a tilt about z).
    VonMises,
}

/// `[packing]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawPacking {
    pub max_steps: Opt<u64>,
    pub jam_resolution: Opt<f64>,
    /// `true`, `false` or `"axis"`: checked by validation.
    pub rotation: Opt<toml::Value>,
    pub max_turn: Opt<f64>,
    pub restore: Opt<bool>,
    pub effort: Opt<f64>,
    pub unjam: Opt<String>,
    pub gap: Opt<f64>,
    pub time_limit: Opt<f64>,
}

/// `[output]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawOutput {
    pub dir: Opt<String>,
    pub grains_csv: Opt<bool>,
    pub summary_json: Opt<bool>,
    pub vtk: Opt<bool>,
    pub vtk_resolution: Opt<i64>,
    pub periodic_images: Opt<bool>,
    pub centers: Opt<bool>,
    pub rve: Opt<bool>,
    /// An integer or `[nx, ny, nz]`: checked by validation.
    pub rve_resolution: Opt<toml::Value>,
    pub rve_voxel_size: Opt<f64>,
    pub rve_fill: Opt<RawFill>,
    pub sections_png: Opt<bool>,
    pub statistics_png: Opt<bool>,
    pub packing_png: Opt<bool>,
    pub damask: Opt<bool>,
    pub abaqus: Opt<bool>,
    pub mesh: Opt<bool>,
    pub mesh_size: Opt<f64>,
    pub mesh_order: Opt<i64>,
    pub mesh_fill: Opt<RawFill>,
}

/// `output.rve_fill`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum RawFill {
    Grains,
    Matrix,
}
