//! The grains as the loop sees them: shapes at target size, moving centres and (when
//! the scene lets them rotate) orientations. With a gap (`packing.gap`), the loop's
//! shapes are the grains inflated by `1 + gap`, and the volumes are the grains' own.

use super::grains::{turn_angle, turn_vector};
use super::PackError;
use crate::contact::Dimension;
use crate::contact::{dot, Ellipsoid, PreparedEllipsoid};
use crate::octree::{wrap_coordinate, BoxShape, Sphere};
use crate::scene::{Boundary, Domain, GrainSpec, Rotation};
use rayon::prelude::*;

/// Grains one rayon task takes in a loop over the grains that does a few arithmetic
/// operations each (their travel, their move, the largest displacement).
pub(super) const GRAINS_PER_TASK: usize = 8192;

/// Everything about the grains at scale 1 (target sizes), and their centres.
/// The shapes (semi-axes, prepared shapes, half-widths, radii) are inflated by
/// `1 + gap`: two of them apart means the grains themselves keep the gap.
pub(crate) struct State {
    pub centres: Vec<[f64; 3]>,
    /// Orientations `[w, x, y, z]`; change only when the grains may rotate.
    pub quaternions: Vec<[f64; 4]>,
    /// The orientations as drawn, which `max_turn` measures turns from.
    pub drawn: Vec<[f64; 4]>,
    /// The axis each grain may turn about under [`Rotation::Axis`].
    pub turn_axes: Vec<Option<[f64; 3]>>,
    /// Target semi-axes, inflated by `1 + gap`.
    pub axes: Vec<[f64; 3]>,
    /// Whether each grain is a sphere (three equal semi-axes): no ellipsoid maths.
    pub round: Vec<bool>,
    /// Prepared shapes at their target size and current orientation.
    pub shapes: Vec<PreparedEllipsoid>,
    /// Volumes of the grains themselves (not inflated) at target size.
    pub volumes: Vec<f64>,
    /// Their sum.
    pub total_volume: f64,
    /// Half-widths `√Q_kk` along the box axes at target size, for the walls.
    pub half_widths: Vec<[f64; 3]>,
    /// The largest bounding radius at target size.
    pub max_bounding_radius: f64,
    /// Their mean (a grain's bounding radius, its largest semi-axis, does not change
    /// as it turns).
    pub mean_bounding_radius: f64,
    /// The grains' mean squared inscribed radius: the unit of the loop's energies (a
    /// pair overlapping by `δ` of the scale has energy about `4 ρ² δ²`), which the
    /// jamming test and the descent read overlaps from.
    pub mean_rho2: f64,
    /// The relative margin kept from the walls ([`WALL_MARGIN`], plus
    /// [`INFLATION_ROUNDING`] with a gap).
    pub wall_margin: f64,
    pub domain: Domain,
    pub box_shape: BoxShape,
}

impl State {
    /// The grains of `specs` in `domain`, their shapes inflated by `1 + gap`.
    pub fn new(specs: &[GrainSpec], domain: &Domain, gap: f64) -> Result<Self, PackError> {
        if specs.is_empty() {
            return Err(PackError::Empty);
        }
        if specs.len() >= u32::MAX as usize {
            return Err(PackError::TooMany(specs.len()));
        }
        let box_shape = domain.box_shape()?;
        let n = specs.len();
        let mut state = Self {
            centres: vec![[0.0; 3]; n],
            quaternions: specs.iter().map(|s| s.quaternion).collect(),
            drawn: specs.iter().map(|s| s.quaternion).collect(),
            turn_axes: specs.iter().map(|s| s.turn_axis).collect(),
            axes: specs
                .iter()
                .map(|s| s.semi_axes.map(|a| a * (1.0 + gap)))
                .collect(),
            round: specs
                .iter()
                .map(|s| s.semi_axes.iter().all(|&a| a == s.semi_axes[0]))
                .collect(),
            shapes: Vec::with_capacity(n),
            volumes: Vec::with_capacity(n),
            total_volume: 0.0,
            half_widths: Vec::with_capacity(n),
            max_bounding_radius: 0.0,
            mean_bounding_radius: 0.0,
            mean_rho2: 0.0,
            wall_margin: if gap > 0.0 {
                WALL_MARGIN + INFLATION_ROUNDING
            } else {
                WALL_MARGIN
            },
            domain: *domain,
            box_shape,
        };
        for (id, spec) in specs.iter().enumerate() {
            let (shape, widths) = state.shape_of(id, spec.quaternion)?;
            state.volumes.push(domain.dimension.measure(spec.semi_axes));
            state.max_bounding_radius = state.max_bounding_radius.max(shape.bounding_radius());
            state.shapes.push(shape);
            state.half_widths.push(widths);
        }
        state.total_volume = state.volumes.iter().sum();
        let radii = state.shapes.iter().map(|e| e.bounding_radius());
        state.mean_bounding_radius = radii.sum::<f64>() / n as f64;
        let rho2 = state.shapes.iter().map(|e| e.inscribed_radius().powi(2));
        state.mean_rho2 = rho2.sum::<f64>() / n as f64;
        Ok(state)
    }

    /// The prepared shape and half-widths of grain `id` at orientation `q`.
    pub fn shape_of(
        &self,
        id: usize,
        q: [f64; 4],
    ) -> Result<(PreparedEllipsoid, [f64; 3]), PackError> {
        let bad = |source| PackError::Grain { id, source };
        let e = Ellipsoid::new(self.axes[id], q).map_err(bad)?;
        let shape = PreparedEllipsoid::with_semi_axes(&e, self.axes[id]).map_err(bad)?;
        Ok((shape, [e.q[0].sqrt(), e.q[3].sqrt(), e.q[5].sqrt()]))
    }

    /// Turns each grain `id` of `turns` to its orientation `q` (unit quaternions), the
    /// new shapes prepared in parallel.
    pub fn set_orientations(&mut self, turns: &[(usize, [f64; 4])]) -> Result<(), PackError> {
        let shapes = turns
            .par_iter()
            .with_min_len(TURNS_PER_TASK)
            .map(|&(id, q)| self.shape_of(id, q))
            .collect::<Result<Vec<_>, _>>()?;
        for (&(id, q), (shape, widths)) in turns.iter().zip(shapes) {
            self.quaternions[id] = q;
            self.shapes[id] = shape;
            self.half_widths[id] = widths;
        }
        Ok(())
    }

    /// Turns grain `id` to orientation `q`, its shape and half-widths at `q` given.
    pub fn set_shape(&mut self, id: usize, q: [f64; 4], shape: (PreparedEllipsoid, [f64; 3])) {
        self.quaternions[id] = q;
        self.shapes[id] = shape.0;
        self.half_widths[id] = shape.1;
    }

    /// The part of torque `t` grain `i` may follow under `mode`.
    pub fn allowed_torque(&self, i: usize, t: [f64; 3], mode: Rotation) -> [f64; 3] {
        match (mode, self.turn_axes[i]) {
            (Rotation::Free, _) => t,
            (Rotation::Axis, Some(a)) => {
                let along = dot(&a, &t);
                a.map(|x| along * x)
            }
            _ => [0.0; 3],
        }
    }

    /// Whether orientation `q` of grain `i` is within `max_turn` radians of its drawn
    /// one.
    pub fn within_turn(&self, i: usize, q: [f64; 4], max_turn: f64) -> bool {
        max_turn >= std::f64::consts::PI || turn_angle(self.drawn[i], q) <= max_turn
    }

    /// The rotation vector taking grain `i` from its drawn orientation to its current
    /// one.
    pub fn turn(&self, i: usize) -> [f64; 3] {
        turn_vector(self.drawn[i], self.quaternions[i])
    }

    pub fn len(&self) -> usize {
        self.centres.len()
    }

    /// Bounding spheres at scale `s`, each grown by `pad`.
    pub fn spheres(&self, s: f64, pad: f64, out: &mut Vec<Sphere>) {
        // Written in place (the resize only fills a new list): collecting in parallel
        // would hold a second list at the memory's peak.
        let unset = Sphere {
            id: 0,
            centre: [0.0; 3],
            radius: 0.0,
        };
        out.resize(self.len(), unset);
        (out.par_iter_mut())
            .zip(&self.centres)
            .zip(&self.shapes)
            .enumerate()
            .with_min_len(GRAINS_PER_TASK)
            .for_each(|(id, ((o, c), e))| {
                *o = Sphere {
                    id: id as u32,
                    centre: *c,
                    radius: s * e.bounding_radius() + pad,
                }
            });
    }

    /// Packing fraction at scale `s` (areas scale by `s²` in 2D).
    pub fn fraction(&self, s: f64) -> f64 {
        let power = match self.domain.dimension {
            Dimension::Three => s * s * s,
            Dimension::Two => s * s,
        };
        power * self.total_volume / self.domain.volume()
    }

    /// Wraps every centre into `[0, L)` in a periodic box; in a walled box, puts it
    /// inside the box (the walls' forces keep the grains themselves inside).
    pub fn wrap(&mut self) {
        let size = self.domain.size;
        let periodic = self.domain.boundary == Boundary::Periodic;
        (self.centres.par_iter_mut())
            .with_min_len(GRAINS_PER_TASK)
            .for_each(|c| {
                for k in 0..3 {
                    c[k] = if periodic {
                        wrap_coordinate(c[k], size[k])
                    } else {
                        c[k].clamp(0.0, size[k])
                    };
                }
            });
    }

    /// Whether grain `i` at scale `s` lies inside the walls with the wall margin.
    pub fn inside_walls(&self, i: usize, s: f64) -> bool {
        let (c, w, size) = (self.centres[i], self.half_widths[i], self.domain.size);
        (0..3).all(|k| {
            let half = s * w[k] * (1.0 + self.wall_margin);
            c[k] >= half && c[k] <= size[k] - half
        })
    }
}

/// Turned grains one rayon task prepares at least: preparing one shape is too little
/// work to be worth a task of its own.
const TURNS_PER_TASK: usize = 64;

/// Relative margin kept between a grain and a wall, so that the rounding of
/// `c ± s·√Q_kk` never puts a grain a hair outside: `4 ε` per the three roundings.
pub(crate) const WALL_MARGIN: f64 = 4.0 * f64::EPSILON;

/// Added to [`WALL_MARGIN`] with a gap: the loop's half-widths come from semi-axes
/// multiplied by `1 + gap` (one rounding, half an ε after the square root), and the
/// final check multiplies the grain's own half-width by `1 + gap` (one more):
/// `2 ε`, doubled for room.
pub(crate) const INFLATION_ROUNDING: f64 = 4.0 * f64::EPSILON;
