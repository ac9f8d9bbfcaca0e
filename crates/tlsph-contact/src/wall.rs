//! A fixed rigid plane (e.g. an anvil), or a flat wall of finite size: a penalty spring pushes
//! back every particle whose half-spacing sphere penetrates the wall, and optional Coulomb
//! friction on the touching particles (numerics.md §13 `[C]`). Depends on current positions and velocities only. A
//! plane moving by d(t) at v_w is this plane seen from the wall: pass x − d(t) and v − v_w
//! (the solver's moving walls do so).

use tlsph_math::{vector_to_3d, Tensor, Vector, Vector3};

/// Penalty stiffness in units of m (c0/h)²: the contact oscillator then has ω = 2 c0/h, so
/// ω Δt = 2 C_cfl ≤ 1.6 for C_cfl ≤ 0.8 — inside the leap-frog limit ω Δt < 2 without
/// reducing the CFL step. Penetration under a contact stress σ is about 0.36 (σ/M) Δx.
pub const WALL_STIFFNESS_FACTOR: f64 = 4.0;

/// The per-particle penalty law shared by every wall shape (numerics.md §13 `[C]`): each
/// particle is a sphere of radius Δx/2 on a spring of stiffness per mass
/// WALL_STIFFNESS_FACTOR c0²/h².
#[derive(Debug, Clone)]
struct PenaltySprings {
    /// Per-particle penalty stiffness divided by mass \[1/s²\].
    stiffness_per_mass: Vec<f64>,
    /// Per-particle contact radius: half its body's spacing \[m\].
    radius: Vec<f64>,
}

impl PenaltySprings {
    fn new(h: &[f64], c0: &[f64], dx: &[f64]) -> Self {
        Self {
            stiffness_per_mass: h
                .iter()
                .zip(c0)
                .map(|(h, c)| WALL_STIFFNESS_FACTOR * c * c / (h * h))
                .collect(),
            radius: dx.iter().map(|d| 0.5 * d).collect(),
        }
    }
}

/// The shape of a rigid wall as its contact law sees it (numerics.md §13 `[C]`): for particle
/// `i` at `x` (in the wall's frame at rest), the penetration δ ≥ 0 of the particle's
/// half-spacing sphere and the unit direction in which the wall pushes it. The spring stores
/// ½ m k δ², and the push k δ is the negative gradient of that energy, so a wall of any shape
/// conserves energy with the particles it touches.
pub trait WallGeometry<const D: usize>: std::fmt::Debug + Send + Sync {
    /// (δ, unit push direction) of particle `i` at `x`; δ = 0 when it does not touch.
    fn contact(&self, i: usize, x: Vector<D>) -> (f64, Vector<D>);

    /// Penalty stiffness per unit mass k/m of particle `i` \[1/s²\].
    fn stiffness_per_mass(&self, i: usize) -> f64;

    /// Contact radius Δx/2 of particle `i` \[m\]: with `contact` giving (δ, n̂) at x, the
    /// nearest point of the wall's surface is x − (Δx/2 − δ) n̂ (see [`surface_point`]).
    fn contact_radius(&self, i: usize) -> f64;
}

/// The point of the wall's surface nearest to particle `i` at `x`, x − (Δx/2 − δ) n̂, from its
/// contact (δ, n̂) with `wall` (numerics.md §13 `[C]`): the foot of the normal on a plane or a
/// disc's face, the nearest rim point past a disc's rim, the radial point on a ball or a
/// cylinder. For a touching particle (δ > 0, or just touching); δ is 0 for any particle clear
/// of the wall, so for those the point is not on the surface.
#[inline]
pub fn surface_point<const D: usize, G: WallGeometry<D> + ?Sized>(
    wall: &G,
    i: usize,
    x: Vector<D>,
    (delta, direction): (f64, Vector<D>),
) -> Vector<D> {
    x - direction * (wall.contact_radius(i) - delta)
}

/// Velocity ω × r of the surface point at `offset` r from the axis of a wall spinning at the
/// angular velocity `omega` about an axis through its centre (ours, not in the theses;
/// numerics.md §13 `[C]`). A wall spins only about an axis of its own symmetry (a plane's or a
/// disc's normal, a cylinder's or a cone's axis, any axis of a ball), so the spin moves its
/// surface without moving its shape: the contact law is unchanged, and only friction, which
/// reads the surface velocity, feels it. In 2D `omega` is (0, 0, ω_z) and r lies in the plane;
/// the result's first D components are returned.
#[inline]
pub fn spin_velocity<const D: usize>(omega: &Vector3, offset: &Vector<D>) -> Vector<D> {
    let v = omega.cross(&vector_to_3d(offset));
    Vector::<D>::from_fn(|k, _| v[k])
}

/// The contact law of a wall given by its distance: a shape with a `distance(x)` method
/// returning (s, n̂), the (signed) distance from `x` to its surface and the outward unit
/// normal there, and a `springs` field, touches particle `i` with δ = Δx/2 − s, pushed along
/// n̂ (numerics.md §13 `[C]`). A shape whose distance is costly names, with `skip_clear`, a
/// method `(x, Δx/2) → Option<direction>` that cheaply finds particles that cannot touch
/// (δ = 0, pushed nowhere): their distance is then not computed.
macro_rules! wall_by_distance {
    ($shape:ident) => {
        wall_by_distance!(@impl $shape, |_: &$shape<D>, _: &Vector<D>, _: f64| None);
    };
    ($shape:ident, skip_clear: $clear:ident) => {
        wall_by_distance!(@impl $shape, |wall: &$shape<D>, x: &Vector<D>, radius: f64| wall
            .$clear(x, radius));
    };
    (@impl $shape:ident, $clear:expr) => {
        impl<const D: usize> WallGeometry<D> for $shape<D> {
            #[inline]
            fn contact(&self, i: usize, x: Vector<D>) -> (f64, Vector<D>) {
                let radius = self.springs.radius[i];
                if let Some(direction) = ($clear)(self, &x, radius) {
                    return (0.0, direction);
                }
                let (s, direction) = self.distance(x);
                ((radius - s).max(0.0), direction)
            }

            #[inline]
            fn stiffness_per_mass(&self, i: usize) -> f64 {
                self.springs.stiffness_per_mass[i]
            }

            #[inline]
            fn contact_radius(&self, i: usize) -> f64 {
                self.springs.radius[i]
            }
        }
    };
}

/// An unbounded rigid plane with the per-particle penalty law (numerics.md §13 `[C]`).
#[derive(Debug, Clone)]
pub struct RigidPlane<const D: usize> {
    point: Vector<D>,
    /// Unit normal into the half-space where particles may be.
    normal: Vector<D>,
    springs: PenaltySprings,
}

impl<const D: usize> RigidPlane<D> {
    /// The plane through `point` with `normal` (normalised here) pointing into the half-space
    /// where particles may be, for particles with smoothing lengths `h`, sound speeds `c0` and
    /// spacings `dx` (one entry per particle).
    pub fn new(point: Vector<D>, normal: Vector<D>, h: &[f64], c0: &[f64], dx: &[f64]) -> Self {
        Self {
            point,
            normal: normal.normalize(),
            springs: PenaltySprings::new(h, c0, dx),
        }
    }

    /// Unit normal into the allowed half-space.
    pub fn normal(&self) -> Vector<D> {
        self.normal
    }

    /// Penetration δ = Δx/2 − (x − point)·n̂ of particle `i` at `x`, or 0.
    #[inline]
    pub fn penetration(&self, i: usize, x: Vector<D>) -> f64 {
        (self.springs.radius[i] - (x - self.point).dot(&self.normal)).max(0.0)
    }

    /// Penalty stiffness per unit mass k/m of particle `i` \[1/s²\].
    #[inline]
    pub fn stiffness_per_mass(&self, i: usize) -> f64 {
        self.springs.stiffness_per_mass[i]
    }

    /// Normal acceleration magnitude (k/m) δ of the penalty spring on particle `i` at `x`; the
    /// spring stores ½ m (k/m) δ².
    #[inline]
    pub fn normal_acceleration(&self, i: usize, x: Vector<D>) -> f64 {
        self.stiffness_per_mass(i) * self.penetration(i, x)
    }
}

impl<const D: usize> WallGeometry<D> for RigidPlane<D> {
    /// Half-space: δ = Δx/2 − (x − point)·n̂, pushed along n̂ (a particle behind the plane is
    /// pushed back to the front).
    #[inline]
    fn contact(&self, i: usize, x: Vector<D>) -> (f64, Vector<D>) {
        (self.penetration(i, x), self.normal)
    }

    #[inline]
    fn stiffness_per_mass(&self, i: usize) -> f64 {
        RigidPlane::stiffness_per_mass(self, i)
    }

    #[inline]
    fn contact_radius(&self, i: usize) -> f64 {
        self.springs.radius[i]
    }
}

/// A flat rigid wall of finite size (ours, not in the theses): the disc of radius R about
/// `point` in the plane normal to n̂ (3D), or the segment of half-length R (2D). It is a
/// plate of zero thickness with a rounded rim: a particle touches it when its half-spacing
/// sphere reaches the disc, δ = Δx/2 − s with s the distance from x to the nearest point of
/// the disc, and is pushed away from that point. In front of the face (in-plane distance from
/// the centre r_t ≤ R) that is the plane's law, δ = Δx/2 − |z| along ±n̂ (z the height above
/// the plane); past the rim the push turns around the edge, so a particle sliding off the
/// edge is released smoothly (s is continuous, and the push is the gradient of the spring's
/// ½ k δ²). Both faces push: a particle cannot pass through the plate where r_t ≤ R, except
/// by a penetration of Δx/2, under a contact stress of about 1.4 M.
#[derive(Debug, Clone)]
pub struct FlatDisc<const D: usize> {
    point: Vector<D>,
    /// Unit normal of the disc's plane (its front face).
    normal: Vector<D>,
    /// R \[m\].
    radius: f64,
    springs: PenaltySprings,
}

impl<const D: usize> FlatDisc<D> {
    /// The disc (segment in 2D) of radius `radius` about `point`, normal to `normal`
    /// (normalised here), for particles with smoothing lengths `h`, sound speeds `c0` and
    /// spacings `dx` (one entry per particle).
    pub fn new(
        point: Vector<D>,
        normal: Vector<D>,
        radius: f64,
        h: &[f64],
        c0: &[f64],
        dx: &[f64],
    ) -> Self {
        Self {
            point,
            normal: normal.normalize(),
            radius,
            springs: PenaltySprings::new(h, c0, dx),
        }
    }

    /// Distance s from `x` to the nearest point of the disc and the unit direction from that
    /// point to `x` (n̂ for a point on the disc itself): the disc is the solid cylinder of
    /// length 0 about its normal (`solid_cylinder_distance`).
    #[inline]
    pub fn distance(&self, x: Vector<D>) -> (f64, Vector<D>) {
        solid_cylinder_distance(x - self.point, &self.normal, self.radius, 0.0)
    }
}

wall_by_distance!(FlatDisc);

/// A rigid ball (ours, not in the theses): the sphere of radius R about `centre` (a disc in
/// 2D: a cylinder in plane strain), e.g. a spherical indenter. A particle touches it when its
/// contact sphere reaches the ball's surface, δ = Δx/2 + R − |x − centre|, and is pushed
/// radially outwards; the push is the gradient of the spring's ½ k δ².
#[derive(Debug, Clone)]
pub struct RigidBall<const D: usize> {
    centre: Vector<D>,
    /// R \[m\].
    radius: f64,
    springs: PenaltySprings,
}

impl<const D: usize> RigidBall<D> {
    /// The ball of radius `radius` about `centre`, for particles with smoothing lengths `h`,
    /// sound speeds `c0` and spacings `dx` (one entry per particle).
    pub fn new(centre: Vector<D>, radius: f64, h: &[f64], c0: &[f64], dx: &[f64]) -> Self {
        Self {
            centre,
            radius,
            springs: PenaltySprings::new(h, c0, dx),
        }
    }
}

impl<const D: usize> WallGeometry<D> for RigidBall<D> {
    /// δ = Δx/2 + R − |x − centre|, pushed along (x − centre)/|x − centre| (along the last
    /// axis for a particle exactly at the centre).
    #[inline]
    fn contact(&self, i: usize, x: Vector<D>) -> (f64, Vector<D>) {
        let offset = x - self.centre;
        let distance = offset.norm();
        let delta = (self.springs.radius[i] + self.radius - distance).max(0.0);
        let direction = if distance > 0.0 {
            offset / distance
        } else {
            let mut last = Vector::<D>::zeros();
            last[D - 1] = 1.0;
            last
        };
        (delta, direction)
    }

    #[inline]
    fn stiffness_per_mass(&self, i: usize) -> f64 {
        self.springs.stiffness_per_mass[i]
    }

    #[inline]
    fn contact_radius(&self, i: usize) -> f64 {
        self.springs.radius[i]
    }
}

/// A unit direction at right angles to the unit `axis`, for a particle exactly on a cylinder's
/// axis (where the radial direction is undefined): the coordinate axis least aligned with it,
/// made normal to it.
fn across_axis<const D: usize>(axis: &Vector<D>) -> Vector<D> {
    let least = axis.iamin();
    let mut e = Vector::<D>::zeros();
    e[least] = 1.0;
    (e - axis * axis[least]).normalize()
}

/// A rigid cylinder of unbounded length (ours, not in the theses): the particles outside the
/// circular cylinder of radius R about the line through `point` along `axis`, e.g. the
/// rollers of a three-point bend or a cylindrical indenter longer than the body. A particle
/// touches it when its contact sphere reaches the surface, δ = Δx/2 + R − r with r the distance
/// from x to the axis, and is pushed away from the axis, across it; the push is the gradient of
/// the spring's ½ k δ². In 2D this is the ball (a cylinder in plane strain); the type is
/// meant for 3D.
#[derive(Debug, Clone)]
pub struct RigidCylinder<const D: usize> {
    point: Vector<D>,
    /// Unit axis direction.
    axis: Vector<D>,
    /// R \[m\].
    radius: f64,
    springs: PenaltySprings,
}

impl<const D: usize> RigidCylinder<D> {
    /// The cylinder of radius `radius` about the line through `point` along `axis`
    /// (normalised here), for particles with smoothing lengths `h`, sound speeds `c0` and
    /// spacings `dx` (one entry per particle).
    pub fn new(
        point: Vector<D>,
        axis: Vector<D>,
        radius: f64,
        h: &[f64],
        c0: &[f64],
        dx: &[f64],
    ) -> Self {
        Self {
            point,
            axis: axis.normalize(),
            radius,
            springs: PenaltySprings::new(h, c0, dx),
        }
    }

    /// The part of x − point across the axis (its length is the distance r to the axis).
    #[inline]
    pub fn radial_offset(&self, x: Vector<D>) -> Vector<D> {
        tlsph_math::across(&(x - self.point), &self.axis)
    }
}

impl<const D: usize> WallGeometry<D> for RigidCylinder<D> {
    /// δ = Δx/2 + R − r, pushed along the radial offset / r (for a particle exactly on the
    /// axis, along the coordinate axis least aligned with the cylinder's, made normal to it).
    #[inline]
    fn contact(&self, i: usize, x: Vector<D>) -> (f64, Vector<D>) {
        let radial = self.radial_offset(x);
        let distance = radial.norm();
        let delta = (self.springs.radius[i] + self.radius - distance).max(0.0);
        let direction = if distance > 0.0 {
            radial / distance
        } else {
            across_axis(&self.axis)
        };
        (delta, direction)
    }

    #[inline]
    fn stiffness_per_mass(&self, i: usize) -> f64 {
        self.springs.stiffness_per_mass[i]
    }

    #[inline]
    fn contact_radius(&self, i: usize) -> f64 {
        self.springs.radius[i]
    }
}

/// A rigid solid cylinder of finite length with flat ends (ours, not in the theses): the
/// particles outside the cylinder of radius R about the segment of length L through `point`
/// (its centre) along `axis`, e.g. a cylindrical punch pressed in deeper than its face, a pin,
/// a rod lying across a body. A particle touches it when its contact sphere reaches the solid,
/// δ = Δx/2 − s with s the signed distance from x to the solid's surface, and is pushed along
/// the outward normal there: radially beside the mantle, along ±axis in front of an end face,
/// away from the nearest rim point past a rim edge (so a particle sliding round the edge is
/// released smoothly, as past a disc's rim). A particle pushed inside is pushed out through
/// the nearest face. The push is the gradient of the spring's ½ k δ².
#[derive(Debug, Clone)]
pub struct FiniteCylinder<const D: usize> {
    point: Vector<D>,
    /// Unit axis direction.
    axis: Vector<D>,
    /// R \[m\].
    radius: f64,
    /// L/2 \[m\].
    half_length: f64,
    springs: PenaltySprings,
}

impl<const D: usize> FiniteCylinder<D> {
    /// The cylinder of radius `radius` and length `length` centred at `point` along `axis`
    /// (normalised here), for particles with smoothing lengths `h`, sound speeds `c0` and
    /// spacings `dx` (one entry per particle).
    pub fn new(
        point: Vector<D>,
        axis: Vector<D>,
        radius: f64,
        length: f64,
        h: &[f64],
        c0: &[f64],
        dx: &[f64],
    ) -> Self {
        Self {
            point,
            axis: axis.normalize(),
            radius,
            half_length: 0.5 * length,
            springs: PenaltySprings::new(h, c0, dx),
        }
    }

    /// Signed distance s from `x` to the cylinder's surface (negative inside) and the unit
    /// outward direction from the nearest surface point towards `x` (the nearest face's
    /// outward normal inside).
    #[inline]
    pub fn distance(&self, x: Vector<D>) -> (f64, Vector<D>) {
        solid_cylinder_distance(x - self.point, &self.axis, self.radius, self.half_length)
    }
}

wall_by_distance!(FiniteCylinder);

/// Signed distance s from the point at `offset` from a solid cylinder's centre to its surface
/// (negative inside), and the unit outward direction from the nearest surface point towards
/// the point (the nearest face's outward normal inside): the cylinder of radius R about the
/// unit `axis`, of length 2 `half_length`. Of length 0 it is a flat disc (a segment in 2D)
/// with a rounded rim, whose distance is never negative. Beside the mantle the push is
/// radial, in front of an end face along ±axis, past a rim away from its nearest point.
#[inline]
fn solid_cylinder_distance<const D: usize>(
    offset: Vector<D>,
    axis: &Vector<D>,
    radius: f64,
    half_length: f64,
) -> (f64, Vector<D>) {
    let along = offset.dot(axis);
    let radial = offset - axis * along;
    let r = radial.norm();
    let end = if along < 0.0 { -axis } else { *axis };
    let radial_unit = if r > 0.0 {
        radial / r
    } else {
        across_axis(axis)
    };
    // Beyond the end face (> 0) and beyond the mantle (> 0).
    let past_end = along.abs() - half_length;
    let past_mantle = r - radius;
    match (past_end > 0.0, past_mantle > 0.0) {
        (true, true) => {
            let s = past_end.hypot(past_mantle);
            (s, (end * past_end + radial_unit * past_mantle) / s)
        }
        (true, false) => (past_end, end),
        (false, true) => (past_mantle, radial_unit),
        // Inside (or on a disc's rim): out through the nearer face, the end face on a tie,
        // so that a disc's face reaches to its rim.
        (false, false) if past_end >= past_mantle => (past_end, end),
        (false, false) => (past_mantle, radial_unit),
    }
}

/// A rigid box (ours, not in the theses): the rectangle (2D) or rectangular block (3D) of
/// edge lengths a_k centred at `centre`, its edges along the orthonormal frame e_k, e.g. a
/// rectangular punch with sharp edges, a die, a step, a block in a body's path. With the
/// particle's offset in the box's frame, q_k = e_k·(x − centre), and p_k = |q_k| − a_k/2 its
/// reach past each pair of faces, the signed distance to the box's surface is
/// s = |max(p, 0)| outside (the nearest point of a face, an edge or a corner) and
/// s = max_k p_k < 0 inside (the nearest face). A particle touches the box when
/// δ = Δx/2 − s > 0 and is pushed along the outward normal at its nearest surface point:
/// along ±e_k in front of a face, away from the nearest edge or corner point past them (so a
/// particle sliding round an edge is released smoothly); one pushed inside is pushed out
/// through the nearest face. The push is the gradient of the spring's ½ k δ².
///
/// With an edge radius ρ ([`RigidBox::with_edge_radius`]) the edges and corners are rounded:
/// the box is the set of points within ρ of the box of edges a_k − 2ρ, so its distance is
/// that box's less ρ, with the same push direction.
#[derive(Debug, Clone)]
pub struct RigidBox<const D: usize> {
    centre: Vector<D>,
    /// The edge directions e_k as columns (orthonormal).
    frame: Tensor<D>,
    /// a_k/2 − ρ: the half edges of the box whose rounding this is \[m\].
    inner_half_size: Vector<D>,
    /// ρ \[m\] (0: sharp edges).
    edge_radius: f64,
    springs: PenaltySprings,
}

impl<const D: usize> RigidBox<D> {
    /// The box of edge lengths `size` (a_k along the frame's column k) centred at `centre`,
    /// for particles with smoothing lengths `h`, sound speeds `c0` and spacings `dx` (one
    /// entry per particle). `frame` must be orthonormal (see [`RigidBox::frame`]).
    pub fn new(
        centre: Vector<D>,
        frame: Tensor<D>,
        size: Vector<D>,
        h: &[f64],
        c0: &[f64],
        dx: &[f64],
    ) -> Self {
        Self {
            centre,
            frame,
            inner_half_size: size * 0.5,
            edge_radius: 0.0,
            springs: PenaltySprings::new(h, c0, dx),
        }
    }

    /// The same box with its edges and corners rounded to the radius `radius` ρ, keeping its
    /// edge lengths (0 ≤ ρ ≤ a_k/2, which the caller checks; a_k/2 on every edge is a ball).
    pub fn with_edge_radius(self, radius: f64) -> Self {
        Self {
            inner_half_size: self.inner_half_size.add_scalar(self.edge_radius - radius),
            edge_radius: radius,
            ..self
        }
    }

    /// The box's frame from its `normal` and, in 3D, its `axis` (neither need be unit): the
    /// last edge e_{D−1} along the normal; in 2D e_0 = (n_y, −n_x), the normal turned a
    /// quarter clockwise; in 3D e_0 along the axis and e_1 = e_2 × e_0, a right-handed frame.
    /// So the normal z and the axis x give the coordinate axes, and a box's `size` lists its
    /// edges along (e_0, e_1[, e_2]). An error says why there is no frame: a zero or
    /// non-finite direction, an axis not at right angles to the normal (to 1e-9 in the cosine)
    /// or a 1D scene.
    pub fn frame(normal: Vector<D>, axis: Vector<D>) -> Result<Tensor<D>, String> {
        let unit = |v: Vector<D>, name: &str| {
            let length = v.norm();
            if length > 0.0 && length.is_finite() {
                Ok(v / length)
            } else {
                Err(format!("the box's {name} must be finite and non-zero"))
            }
        };
        let normal = unit(normal, "normal")?;
        match D {
            2 => Ok(Tensor::<D>::from_fn(|r, c| match (r, c) {
                (0, 0) => normal[1],
                (1, 0) => -normal[0],
                (r, _) => normal[r],
            })),
            3 => {
                let axis = unit(axis, "axis")?;
                let cosine = axis.dot(&normal);
                if cosine.abs() > 1e-9 {
                    return Err(format!(
                        "the box's axis must be at right angles to its normal, their cosine is {cosine:.3e}"
                    ));
                }
                // Remove the round-off along the normal so the frame is orthonormal.
                let axis = (axis - normal * cosine).normalize();
                let (e0, e2) = (vector_to_3d(&axis), vector_to_3d(&normal));
                let e1 = e2.cross(&e0);
                Ok(Tensor::<D>::from_fn(|r, c| [e0, e1, e2][c][r]))
            }
            _ => Err(format!("a box needs a 2D or 3D scene, got {D}D")),
        }
    }

    /// Signed distance s from `x` to the box's surface (negative inside) and the unit outward
    /// direction from the nearest surface point towards `x` (the nearest face's outward
    /// normal inside; the first such face on a tie).
    #[inline]
    pub fn distance(&self, x: Vector<D>) -> (f64, Vector<D>) {
        let local = self.frame.tr_mul(&(x - self.centre));
        let side = local.map(|q| if q < 0.0 { -1.0 } else { 1.0 });
        let past = local.abs() - self.inner_half_size;
        let outside = past.map(|p| p.max(0.0));
        let s = outside.norm();
        if s > 0.0 {
            (
                s - self.edge_radius,
                self.frame * outside.component_mul(&side) / s,
            )
        } else {
            let nearest = past.imax();
            (
                past[nearest] - self.edge_radius,
                self.frame.column(nearest) * side[nearest],
            )
        }
    }
}

wall_by_distance!(RigidBox);

/// A rigid cone (ours, not in the theses): the solid cone of half-angle α (between its axis
/// and its flanks) whose tip is at `tip` and which opens along the unit `axis`, unbounded
/// towards its base, with its tip optionally rounded to a sphere of radius ρ tangent to the
/// flanks; in 2D the same law is a wedge (the cone in plane strain). E.g. a conical indenter
/// (a Rockwell diamond, α = 60°, ρ = 0.2 mm; the cone of the same area function as a Vickers
/// or Berkovich pyramid, α = 70.3°), a wedge indenter, a conical penetrator's nose.
///
/// With the offset q = x − a of a point from the apex a = tip + ρ â of the sharp cone whose
/// rounding this is, its height z = q·â along the axis, its distance r from the axis and
/// t = r sin α + z cos α its reach along the flank from the apex, the signed distance to the
/// rounded cone's surface is s = r cos α − z sin α − ρ where t > 0 (beside the flank: negative
/// inside), pushed along the flank's outward normal n̂ = r̂ cos α − â sin α, and s = |q| − ρ
/// where t ≤ 0 (round the tip), pushed along q/|q|. The two agree in value and direction where
/// t = 0, so s is continuously differentiable, and the push k δ n̂ with δ = Δx/2 − s is the
/// gradient of the spring's ½ k δ²; a particle pushed inside is pushed out through the
/// nearer flank.
#[derive(Debug, Clone)]
pub struct RigidCone<const D: usize> {
    /// Apex of the sharp cone, tip + ρ â \[m\].
    apex: Vector<D>,
    /// Unit axis, from the tip into the cone.
    axis: Vector<D>,
    /// (sin α, cos α).
    sin_cos: (f64, f64),
    /// ρ \[m\] (0: a sharp tip).
    tip_radius: f64,
    springs: PenaltySprings,
}

impl<const D: usize> RigidCone<D> {
    /// The cone with its tip at `tip`, opening along `axis` (normalised here), of half-angle
    /// `half_angle` α (radians, 0 < α < π/2, which the caller checks) and with its tip rounded
    /// to `tip_radius` ρ ≥ 0, for particles with smoothing lengths `h`, sound speeds `c0` and
    /// spacings `dx` (one entry per particle).
    pub fn new(
        tip: Vector<D>,
        axis: Vector<D>,
        half_angle: f64,
        tip_radius: f64,
        h: &[f64],
        c0: &[f64],
        dx: &[f64],
    ) -> Self {
        let axis = axis.normalize();
        Self {
            apex: tip + axis * tip_radius,
            axis,
            sin_cos: half_angle.sin_cos(),
            tip_radius,
            springs: PenaltySprings::new(h, c0, dx),
        }
    }

    /// Signed distance s from `x` to the cone's surface (negative inside) and the unit outward
    /// direction from the nearest surface point towards `x` (the nearer flank's outward normal
    /// inside; for a point on the axis inside, the flank across the axis from it along the
    /// coordinate axis least aligned with the cone's).
    #[inline]
    pub fn distance(&self, x: Vector<D>) -> (f64, Vector<D>) {
        let (sin, cos) = self.sin_cos;
        let offset = x - self.apex;
        let height = offset.dot(&self.axis);
        let radial = offset - self.axis * height;
        let r = radial.norm();
        if r * sin + height * cos > 0.0 {
            let radial_unit = if r > 0.0 {
                radial / r
            } else {
                across_axis(&self.axis)
            };
            (
                r * cos - height * sin - self.tip_radius,
                radial_unit * cos - self.axis * sin,
            )
        } else {
            let length = offset.norm();
            let direction = if length > 0.0 {
                offset / length
            } else {
                -self.axis
            };
            (length - self.tip_radius, direction)
        }
    }
}

wall_by_distance!(RigidCone);

/// A rigid regular pyramid (ours, not in the theses; 3D): the solid pyramid of N ≥ 3 faces
/// whose tip is at `tip` and which opens along the unit axis â, unbounded towards its base,
/// every face at the half-angle α to the axis (between the axis and the face's centre line),
/// with its tip optionally rounded to a sphere of radius ρ. E.g. a Vickers indenter (N = 4,
/// α = 68°), a Berkovich indenter (N = 3, α = 65.27°), a cube corner (N = 3, α = 35.26°).
///
/// With the frame (ê₁, ê₂ = â × ê₁, â), ê₁ pointing from the axis towards the middle of the
/// first face, face j faces r̂_j = cos θ_j ê₁ + sin θ_j ê₂, θ_j = 2πj/N, and has the outward
/// unit normal n̂_j = r̂_j cos α − â sin α; edge j, between faces j and j + 1, runs from the apex
/// along ê_j ∝ â + r̂ tan α / cos(π/N), r̂ at θ_j + π/N. The sharp pyramid is the convex cone
/// {q : n̂_j·q ≤ 0 for every j} with q = x − a the offset from its apex a = tip + ρ â; the
/// rounded one is the set of points within ρ of it, so its signed distance is the sharp one's
/// less ρ, and its foremost point stays at `tip`. The sharp pyramid's signed distance is
/// s = max_j n̂_j·q ≤ 0 inside (the nearest face, pushed out along its normal), and outside the
/// distance to the nearest point of its surface: the foot q − (n̂_j·q) n̂_j on face j where
/// that foot lies within the face (on the inner side of both neighbouring faces), or else the
/// nearest point of an edge (or the apex). The push along the unit vector from that point to
/// x is the gradient of the spring's ½ k δ², δ = Δx/2 − s (the penalty law of numerics.md §13
/// `[C]`).
#[derive(Debug, Clone)]
pub struct RigidPyramid<const D: usize> {
    /// Apex of the sharp pyramid, tip + ρ â \[m\].
    apex: Vector<D>,
    /// The faces' outward unit normals n̂_j.
    face_normals: Vec<Vector<D>>,
    /// The edges' unit directions ê_j from the apex (edge j between faces j and j + 1).
    edges: Vec<Vector<D>>,
    /// ρ \[m\] (0: a sharp tip).
    tip_radius: f64,
    springs: PenaltySprings,
}

impl<const D: usize> RigidPyramid<D> {
    /// The pyramid with its tip at `tip`, opening along `axis`, its first face towards
    /// `face_direction` (at right angles to the axis; neither need be unit), of `sides` N
    /// faces at the half-angle `half_angle` α (radians) to the axis and with its tip rounded
    /// to `tip_radius` ρ, for particles with smoothing lengths `h`, sound speeds `c0` and
    /// spacings `dx` (one entry per particle). An error says why there is none: not a 3D
    /// scene, fewer than 3 sides, an axis or a face direction zero or not finite, the two not
    /// at right angles (to 1e-9 in the cosine), α not within 0 < α < π/2, ρ not finite and ≥ 0.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        tip: Vector<D>,
        axis: Vector<D>,
        face_direction: Vector<D>,
        sides: usize,
        half_angle: f64,
        tip_radius: f64,
        (h, c0, dx): (&[f64], &[f64], &[f64]),
    ) -> Result<Self, String> {
        let (axis, first_face) = Self::frame(axis, face_direction)?;
        if sides < 3 {
            return Err(format!("a pyramid needs at least 3 sides, got {sides}"));
        }
        if !(half_angle > 0.0 && half_angle < std::f64::consts::FRAC_PI_2) {
            return Err(format!(
                "a pyramid's half-angle must lie between 0 and 90°, got {}°",
                half_angle.to_degrees()
            ));
        }
        if !(tip_radius.is_finite() && tip_radius >= 0.0) {
            return Err(format!(
                "a pyramid's tip radius must be finite and ≥ 0, got {tip_radius}"
            ));
        }
        let second = axis.cross(&first_face);
        let radial = |angle: f64| first_face * angle.cos() + second * angle.sin();
        let (sin, cos) = half_angle.sin_cos();
        let sector = std::f64::consts::TAU / sides as f64;
        let edge_slope = half_angle.tan() / (0.5 * sector).cos();
        let in_d = |v: Vector3| Vector::<D>::from_fn(|k, _| v[k]);
        let face_normals = (0..sides)
            .map(|j| in_d(radial(j as f64 * sector) * cos - axis * sin))
            .collect();
        let edges = (0..sides)
            .map(|j| in_d((axis + radial((j as f64 + 0.5) * sector) * edge_slope).normalize()))
            .collect();
        Ok(Self {
            apex: tip + in_d(axis) * tip_radius,
            face_normals,
            edges,
            tip_radius,
            springs: PenaltySprings::new(h, c0, dx),
        })
    }

    /// The unit axis â and the unit direction ê₁ towards the first face from `axis` and
    /// `face_direction`, or why there are none (see [`RigidPyramid::new`]).
    fn frame(axis: Vector<D>, face_direction: Vector<D>) -> Result<(Vector3, Vector3), String> {
        if D != 3 {
            return Err(format!(
                "a pyramid needs a 3D scene (in 2D a wedge is a cone), got {D}D"
            ));
        }
        let unit = |v: Vector<D>, name: &str| {
            let length = v.norm();
            if length > 0.0 && length.is_finite() {
                Ok(vector_to_3d(&(v / length)))
            } else {
                Err(format!("a pyramid's {name} must be finite and non-zero"))
            }
        };
        let axis = unit(axis, "axis")?;
        let face = unit(face_direction, "face direction")?;
        let cosine = axis.dot(&face);
        if cosine.abs() > 1e-9 {
            return Err(format!(
                "a pyramid's face direction must be at right angles to its axis, their cosine is {cosine:.3e}"
            ));
        }
        // Remove the round-off along the axis so the frame is orthonormal.
        Ok((axis, (face - axis * cosine).normalize()))
    }

    /// The faces' outward unit normals n̂_j, face j towards θ_j = 2πj/N from ê₁.
    pub fn face_normals(&self) -> &[Vector<D>] {
        &self.face_normals
    }

    /// The edges' unit directions ê_j from the apex, edge j between faces j and j + 1: the
    /// sharp pyramid is the apex plus every non-negative combination of them.
    pub fn edges(&self) -> &[Vector<D>] {
        &self.edges
    }

    /// The apex of the sharp pyramid whose rounding this is, tip + ρ â (the tip itself when
    /// sharp) \[m\].
    pub fn apex(&self) -> Vector<D> {
        self.apex
    }

    /// Signed distance s from `x` to the pyramid's surface (negative inside) and the unit
    /// outward direction from the nearest surface point towards `x` (the nearest face's
    /// outward normal inside; the first such face on a tie).
    #[inline]
    pub fn distance(&self, x: Vector<D>) -> (f64, Vector<D>) {
        let offset = x - self.apex;
        let (nearest, height) = self.highest_face(&offset);
        if height <= 0.0 {
            return (height - self.tip_radius, self.face_normals[nearest]);
        }
        let heights = |j: usize| self.face_normals[j].dot(&offset);
        let n = self.face_normals.len();
        let mut best = (f64::INFINITY, self.face_normals[nearest]);
        for j in 0..n {
            let h = heights(j);
            let foot = offset - self.face_normals[j] * h;
            let within = |k: usize| self.face_normals[k].dot(&foot) <= 0.0;
            if h > 0.0 && h < best.0 && within((j + n - 1) % n) && within((j + 1) % n) {
                best = (h, self.face_normals[j]);
            }
        }
        for edge in &self.edges {
            let along = offset.dot(edge).max(0.0);
            let away = offset - edge * along;
            let s = away.norm();
            if s < best.0 {
                best = (s, away / s);
            }
        }
        (best.0 - self.tip_radius, best.1)
    }

    /// For the contact law: `Some(n̂_j)` when `x` stands at least `radius` + ρ above the plane
    /// of a face j, so that it cannot touch (s ≥ that height − ρ) and the search of the faces
    /// and edges for its nearest point is skipped: most particles of a body under an
    /// indenter.
    #[inline]
    fn clear_of(&self, x: &Vector<D>, radius: f64) -> Option<Vector<D>> {
        let (nearest, height) = self.highest_face(&(x - self.apex));
        (height - self.tip_radius >= radius).then(|| self.face_normals[nearest])
    }

    /// The face whose plane `offset` (from the apex) stands highest above, and that height
    /// max_j n̂_j·q: the sharp pyramid's signed distance inside, a lower bound on it outside
    /// (the solid lies behind every face's plane).
    #[inline]
    fn highest_face(&self, offset: &Vector<D>) -> (usize, f64) {
        let mut best = (0, self.face_normals[0].dot(offset));
        for (j, normal) in self.face_normals.iter().enumerate().skip(1) {
            let h = normal.dot(offset);
            if h > best.1 {
                best = (j, h);
            }
        }
        best
    }
}

wall_by_distance!(RigidPyramid, skip_clear: clear_of);

/// Coulomb friction coefficients of a surface: the kinetic μ_k of sliding, the static
/// μ_s ≥ μ_k that bounds the force holding a particle at rest, and how the coefficient of a
/// sliding contact falls from μ_s to μ_k with its sliding speed (numerics.md §13 `[C]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionCoefficients {
    /// Kinetic coefficient μ_k ≥ 0.
    pub kinetic: f64,
    /// Static coefficient μ_s ≥ μ_k.
    pub static_coefficient: f64,
    /// Exponential decay coefficient d_c ≥ 0 \[s/m\] of the sliding coefficient,
    /// μ(v) = μ_k + (μ_s − μ_k) exp(−d_c v) at sliding speed v (the exponential-decay law of
    /// finite-element codes' friction models); `None`: a sliding contact drops to μ_k at once.
    pub decay: Option<f64>,
}

impl FrictionCoefficients {
    /// One coefficient μ for both sticking and sliding.
    pub fn single(mu: f64) -> Self {
        Self {
            kinetic: mu,
            static_coefficient: mu,
            decay: None,
        }
    }

    /// Checks μ_k (finite, ≥ 0), μ_s (finite, ≥ μ_k) and d_c (finite, ≥ 0); the error says
    /// which is wrong.
    pub fn check(&self) -> Result<(), String> {
        let kinetic = self.kinetic;
        if !(kinetic.is_finite() && kinetic >= 0.0) {
            return Err(format!(
                "the friction coefficient must be finite and ≥ 0, got {kinetic}"
            ));
        }
        let static_coefficient = self.static_coefficient;
        if !(static_coefficient.is_finite() && static_coefficient >= kinetic) {
            return Err(format!(
                "the static friction coefficient must be finite and ≥ the kinetic {kinetic}, got {static_coefficient}"
            ));
        }
        match self.decay {
            Some(decay) if !(decay.is_finite() && decay >= 0.0) => Err(format!(
                "the friction decay coefficient must be finite and ≥ 0, got {decay}"
            )),
            _ => Ok(()),
        }
    }

    /// Whether the surface has friction at all (μ_s > 0: it can hold, even when μ_k = 0).
    pub fn is_frictional(&self) -> bool {
        self.static_coefficient > 0.0
    }

    /// Friction force per unit of normal force, given the stick `demand` (the force that
    /// would stop the sliding within the step, per unit of normal force) and the sliding
    /// `speed`: the demand itself while it is at most μ_s (the contact sticks), else the
    /// sliding coefficient μ(speed) = μ_k + (μ_s − μ_k) exp(−d_c speed), or μ_k without a
    /// decay coefficient. With one coefficient this is min(μ, demand). The sliding force never
    /// exceeds the stopping one, so friction never reverses the sliding. Shared by the wall
    /// and penalty-contact laws.
    #[inline]
    pub fn coefficient(&self, demand: f64, speed: f64) -> f64 {
        if demand <= self.static_coefficient {
            demand
        } else if let Some(decay) = self.decay {
            self.kinetic + (self.static_coefficient - self.kinetic) * (-decay * speed).exp()
        } else {
            self.kinetic
        }
    }
}

/// Coulomb friction of a rigid surface on one touching particle (numerics.md §13 `[C]`).
///
/// With a_n the normal acceleration of the wall's spring, v* the particle's velocity after the
/// step's earlier kicks (relative to the surface's) and v*_t its part tangential to the unit
/// `normal`, the friction acceleration is
///
///   a_t = −v*_t / Δt_kick                 if |v*_t| / Δt_kick ≤ μ_s a_n (the particle sticks),
///   a_t = −μ_k a_n v*_t / |v*_t|          otherwise (it slides),
///
/// so a particle is held while the force that stops its tangential motion within this kick is
/// at most μ_s times its normal force, and slides against the kinetic force μ_k m a_n when
/// more is needed. With μ_s = μ_k this is a_t = −min(μ a_n, |v*_t|/Δt) v̂*_t. It needs no slip
/// regularisation, no history and no time-step limit, and never reverses a particle's sliding
/// direction (μ_k ≤ μ_s). Zero when the particle does not touch (a_n = 0) or does not slide.
#[inline]
pub fn wall_friction_acceleration<const D: usize>(
    normal_acceleration: f64,
    velocity: Vector<D>,
    normal: Vector<D>,
    friction: FrictionCoefficients,
    kick: f64,
) -> Vector<D> {
    let v_t = tlsph_math::across(&velocity, &normal);
    let speed = v_t.norm();
    if !(normal_acceleration > 0.0 && speed > 0.0) {
        return Vector::zeros();
    }
    let demand = speed / (kick * normal_acceleration);
    v_t * (-normal_acceleration * friction.coefficient(demand, speed) / speed)
}
