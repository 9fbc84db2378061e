//! The grains as the loop sees them: fixed shapes at unit scale, moving centres.

use super::PackError;
use crate::contact::{Ellipsoid, PreparedEllipsoid};
use crate::io::scene::{Boundary, Domain, GrainSpec};
use crate::octree::{BoxShape, Sphere};

/// Everything about the grains that does not change while packing (at scale 1), and
/// their centres, which do.
pub(crate) struct State {
    pub centres: Vec<[f64; 3]>,
    /// Prepared shapes at their target size.
    pub shapes: Vec<PreparedEllipsoid>,
    /// Volumes at target size.
    pub volumes: Vec<f64>,
    /// Half-widths `√Q_kk` along the axes at target size, for the walls.
    pub half_widths: Vec<[f64; 3]>,
    /// The largest bounding radius at target size.
    pub max_bounding_radius: f64,
    pub domain: Domain,
    pub box_shape: BoxShape,
}

impl State {
    pub fn new(specs: &[GrainSpec], domain: &Domain) -> Result<Self, PackError> {
        if specs.is_empty() {
            return Err(PackError::Empty);
        }
        if specs.len() >= u32::MAX as usize {
            return Err(PackError::TooMany(specs.len()));
        }
        let mut shapes = Vec::with_capacity(specs.len());
        let mut volumes = Vec::with_capacity(specs.len());
        let mut half_widths = Vec::with_capacity(specs.len());
        for (id, spec) in specs.iter().enumerate() {
            let bad = |e: &dyn std::fmt::Display| PackError::Grain {
                id,
                message: e.to_string(),
            };
            let e = Ellipsoid::new(spec.semi_axes, spec.quaternion).map_err(|e| bad(&e))?;
            shapes.push(PreparedEllipsoid::new(&e).map_err(|e| bad(&e))?);
            volumes.push(e.volume());
            half_widths.push([e.q[0].sqrt(), e.q[3].sqrt(), e.q[5].sqrt()]);
        }
        let box_shape = match domain.boundary {
            Boundary::Periodic => BoxShape::periodic(domain.size),
            Boundary::Reflecting => BoxShape::reflecting(domain.size),
        }
        .map_err(|e| PackError::Domain(e.to_string()))?;
        let max_bounding_radius = shapes
            .iter()
            .fold(0.0f64, |m, e| m.max(e.bounding_radius()));
        Ok(Self {
            centres: vec![[0.0; 3]; specs.len()],
            max_bounding_radius,
            shapes,
            volumes,
            half_widths,
            domain: *domain,
            box_shape,
        })
    }

    pub fn len(&self) -> usize {
        self.centres.len()
    }

    /// Bounding spheres at scale `s`.
    pub fn spheres(&self, s: f64, out: &mut Vec<Sphere>) {
        out.clear();
        out.extend(
            self.centres
                .iter()
                .zip(&self.shapes)
                .enumerate()
                .map(|(id, (c, e))| Sphere {
                    id: id as u32,
                    centre: *c,
                    radius: s * e.bounding_radius(),
                }),
        );
    }

    /// Packing fraction at scale `s`.
    pub fn fraction(&self, s: f64) -> f64 {
        s * s * s * self.volumes.iter().sum::<f64>() / self.domain.volume()
    }

    /// Puts every centre back in the box: wrapped into `[0, L)` when periodic, pushed
    /// inside the walls (by its half-width at scale `s`) when walled.
    pub fn confine(&mut self, s: f64) {
        let size = self.domain.size;
        match self.domain.boundary {
            Boundary::Periodic => {
                for c in &mut self.centres {
                    for k in 0..3 {
                        c[k] = c[k].rem_euclid(size[k]);
                        // rem_euclid can round up to L itself.
                        if c[k] >= size[k] {
                            c[k] = 0.0;
                        }
                    }
                }
            }
            Boundary::Reflecting => {
                for (c, w) in self.centres.iter_mut().zip(&self.half_widths) {
                    for k in 0..3 {
                        let half = s * w[k] * (1.0 + WALL_MARGIN);
                        c[k] = c[k].clamp(half, (size[k] - half).max(half));
                    }
                }
            }
        }
    }
}

/// Relative margin kept between a grain and a wall, so that the rounding of
/// `c ± s·√Q_kk` never puts a grain a hair outside: `4 ε` per the three roundings.
pub(crate) const WALL_MARGIN: f64 = 4.0 * f64::EPSILON;
