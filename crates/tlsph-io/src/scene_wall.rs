//! The `[[wall]]` tables: a rigid plane, disc, ball, cylinder, box, cone or pyramid with its
//! friction and motion, checked against the bodies' starting positions and the symmetry planes
//! (numerics.md §13 `[C]`; the finite shapes are ours).

use crate::scene::{axis_index, history_key, parse_amplitude, point_text, Context, SceneError};
use crate::scene_file::{SymmetryPlaneTable, WallTable};
use tlsph_math::{across, vector_to_3d, Vector, Vector3};
use tlsph_solver::{
    BodyDescription, RampShape, VelocityRamp, WallDescription, WallMotion, WallShape,
};

/// Most faces a pyramid wall may have: its contact costs a few dot products per face and
/// particle, and a pyramid of many more faces is nearly a cone.
const MAX_PYRAMID_SIDES: i64 = 100;

/// The wall of table `w` named `name`, for `bodies` as placed and the scene's
/// `symmetry_planes`.
pub(crate) fn build_wall<const D: usize>(
    ctx: &Context<'_>,
    w: &WallTable,
    name: String,
    bodies: &[BodyDescription<D>],
    symmetry_planes: &[SymmetryPlaneTable],
) -> Result<WallDescription<D>, SceneError> {
    let prefix = format!("wall[{name}]");
    let key = |k: &str| format!("{prefix}.{k}");
    let point = ctx.vector::<D>(&w.point, &key("point"))?;
    let (shape, normal) = wall_shape::<D>(ctx, w, &key)?;
    let unit = normal / normal.norm();
    check_start(ctx, w, &shape, point, unit, bodies, &key)?;
    let friction =
        ctx.friction_coefficients(&w.friction, &w.static_friction, &w.friction_decay, &prefix)?;
    let amplitude = parse_amplitude(
        ctx,
        &w.ramp_time,
        &w.ramp_shape,
        &w.amplitude,
        &w.amplitude_shape,
        &key,
    )?;
    let spin = match &w.spin {
        Some(s) => Some(wall_spin::<D>(
            ctx,
            w,
            s,
            &shape,
            unit,
            &friction,
            symmetry_planes,
            &key,
        )?),
        None => None,
    };
    let spin_ramp = match (&w.spin_ramp_time, spin) {
        (Some(t), Some(_)) => Some(VelocityRamp {
            duration: ctx.positive(t, &key("spin_ramp_time"))?,
            shape: RampShape::Smooth,
        }),
        (Some(t), None) => {
            return Err(ctx.error(
                &t.span(),
                &key("spin_ramp_time"),
                "needs a `spin` to start up".into(),
            ))
        }
        (None, _) => None,
    };
    let history = history_key(&w.ramp_time, &w.amplitude);
    let motion = match (&w.velocity, spin) {
        (Some(v), spin) => {
            let velocity = ctx.vector::<D>(v, &key("velocity"))?;
            // A plane that lies along a symmetry plane's normal, or a cylinder whose axis is
            // that normal, and slides along it would slide the other way in the mirrored half:
            // with friction, not a symmetric model (frictionless, the sliding is not felt; a
            // wall across the normal is mirrored into a second wall, moving as its mirror
            // image; the finite shapes are checked below).
            let lies_along = |a: usize| match shape {
                WallShape::Plane => normal[a] == 0.0,
                WallShape::Cylinder {
                    axis, length: None, ..
                } => axis[a].abs() == axis.norm(),
                WallShape::Cylinder {
                    length: Some(_), ..
                } => false,
                WallShape::Disc { .. }
                | WallShape::Ball { .. }
                | WallShape::Box { .. }
                | WallShape::Cone { .. }
                | WallShape::Pyramid { .. } => false,
            };
            let sliding_across_a_mirror = symmetry_planes.iter().find(|p| {
                axis_index(p.axis.get_ref()).is_some_and(|a| {
                    a < D && lies_along(a) && velocity[a] != 0.0 && friction.is_frictional()
                })
            });
            if let Some(plane) = sliding_across_a_mirror {
                return Err(ctx.error(
                    &v.span(),
                    &key("velocity"),
                    format!(
                        "slides along {}, the normal of a symmetry plane: its friction would drag the mirrored half the other way, so the model is not symmetric",
                        plane.axis.get_ref()
                    ),
                ));
            }
            Some(WallMotion {
                velocity,
                spin,
                amplitude,
                spin_ramp,
            })
        }
        (None, spin) => {
            if let Some((k, span)) = history {
                return Err(ctx.error(
                    &span,
                    &key(k),
                    if spin.is_some() {
                        format!("a wall that only spins has no velocity to scale in time; give a `velocity` or drop `{k}` (a spin starts up with `spin_ramp_time`)")
                    } else {
                        format!("a fixed wall has nothing to scale in time; give a `velocity` or drop `{k}`")
                    },
                ));
            }
            spin.map(|spin| WallMotion {
                velocity: Vector::<D>::zeros(),
                spin: Some(spin),
                amplitude,
                spin_ramp,
            })
        }
    };
    let sliding = |a: usize| motion.as_ref().is_some_and(|m| m.velocity[a] != 0.0);
    check_symmetry(ctx, w, &shape, point, unit, sliding, symmetry_planes, &key)?;
    let report_moment = match &w.report_moment {
        Some(flag) if D == 1 && *flag.get_ref() => {
            return Err(ctx.error(
                &flag.span(),
                &key("report_moment"),
                "a 1D wall's force has no moment (every force and lever lies along x)".into(),
            ))
        }
        Some(flag) => *flag.get_ref(),
        None => false,
    };
    Ok(WallDescription {
        name,
        point,
        normal,
        friction,
        motion,
        shape,
        report_moment,
    })
}

/// The wall's shape from `shape`, `radius`, `normal`, `axis`, `length`, `size`, `edge_radius`,
/// `half_angle`, `tip_radius`, `sides` and `face_direction`, and its normal as given (the last
/// coordinate axis for a ball, a cylinder, a cone or a pyramid, which have none).
fn wall_shape<const D: usize>(
    ctx: &Context<'_>,
    w: &WallTable,
    key: &dyn Fn(&str) -> String,
) -> Result<(WallShape<D>, Vector<D>), SceneError> {
    #[derive(Clone, Copy, PartialEq)]
    enum Kind {
        Plane,
        Disc,
        Ball,
        Cylinder,
        Box,
        Cone,
        Pyramid,
    }
    let default_kind = if w.radius.is_some() {
        Kind::Disc
    } else {
        Kind::Plane
    };
    let kind = ctx.keyword(
        w.shape.as_ref(),
        &key("shape"),
        "wall shape",
        default_kind,
        &[
            ("plane", Kind::Plane),
            ("disc", Kind::Disc),
            ("ball", Kind::Ball),
            ("cylinder", Kind::Cylinder),
            ("box", Kind::Box),
            ("cone", Kind::Cone),
            ("pyramid", Kind::Pyramid),
        ],
    )?;
    let shape_span = w.shape.as_ref().map_or(w.name.span(), |s| s.span());
    let refuse = |span: std::ops::Range<usize>, field: &str, message: &str| {
        Err(ctx.error(&span, &key(field), message.into()))
    };
    if kind == Kind::Cylinder && D != 3 {
        return Err(ctx.error(
            &shape_span,
            &key("shape"),
            format!("a cylinder wall needs a 3D scene, got {D}D (in 2D, shape = \"ball\" is the cylinder in plane strain)"),
        ));
    }
    if kind == Kind::Pyramid && D != 3 {
        return Err(ctx.error(
            &shape_span,
            &key("shape"),
            format!(
                "a pyramid wall needs a 3D scene, got {D}D (in 2D, shape = \"cone\" is a wedge)"
            ),
        ));
    }
    if matches!(kind, Kind::Box | Kind::Cone) && D < 2 {
        return Err(ctx.error(
            &shape_span,
            &key("shape"),
            "a 1D wall is a point; a box or a cone needs a 2D or 3D scene".into(),
        ));
    }
    let radius = match (&w.radius, kind) {
        (None, Kind::Plane | Kind::Box | Kind::Cone | Kind::Pyramid) => 0.0,
        (Some(r), Kind::Cone | Kind::Pyramid) => {
            return Err(ctx.error(
                &r.span(),
                &key("radius"),
                "a cone or pyramid wall has a `half_angle`, and a `tip_radius` if its tip is rounded, not a radius".into(),
            ))
        }
        (Some(r), Kind::Box) => {
            return Err(ctx.error(
                &r.span(),
                &key("radius"),
                "a box wall has a `size` (its edge lengths), not a radius".into(),
            ))
        }
        (Some(r), Kind::Plane) => {
            return Err(ctx.error(
                &r.span(),
                &key("radius"),
                "a plane wall has no radius (shape = \"disc\", \"ball\" or \"cylinder\" has)"
                    .into(),
            ))
        }
        (None, _) => {
            return Err(ctx.error(
                &shape_span,
                &key("radius"),
                "is required by a disc, ball or cylinder wall".into(),
            ))
        }
        (Some(r), _) if D < 2 => {
            return Err(ctx.error(
                &r.span(),
                &key("radius"),
                "a 1D wall is a point; a finite wall needs a 2D or 3D scene".into(),
            ))
        }
        (Some(r), _) => ctx.positive(r, &key("radius"))?,
    };
    let non_zero = |v: &toml::Spanned<Vec<f64>>, field: &str| {
        let direction = ctx.vector::<D>(v, &key(field))?;
        if direction.norm() == 0.0 {
            return Err(ctx.error(&v.span(), &key(field), "must not be zero".into()));
        }
        Ok(direction)
    };
    // A ball, a cylinder, a cone or a pyramid has no normal; a box's is optional; a plane and
    // a disc need one. The last axis stands in.
    let radial = matches!(
        kind,
        Kind::Ball | Kind::Cylinder | Kind::Cone | Kind::Pyramid
    );
    let normal =
        match (&w.normal, radial) {
            (None, false) if kind == Kind::Box => {
                let mut last = Vector::<D>::zeros();
                last[D - 1] = 1.0;
                last
            }
            (Some(n), true) => return Err(ctx.error(
                &n.span(),
                &key("normal"),
                "a ball, cylinder, cone or pyramid wall has no normal (it is placed by its point, and turned by its axis)"
                    .into(),
            )),
            (None, true) => {
                let mut last = Vector::<D>::zeros();
                last[D - 1] = 1.0;
                last
            }
            (None, false) => {
                return Err(ctx.error(
                    &w.name.span(),
                    &key("normal"),
                    "is required by a plane or disc wall".into(),
                ))
            }
            (Some(n), false) => non_zero(n, "normal")?,
        };
    let axis = match (&w.axis, kind) {
        (Some(a), Kind::Cylinder | Kind::Cone | Kind::Pyramid) => non_zero(a, "axis")?,
        (None, Kind::Cylinder | Kind::Cone | Kind::Pyramid) => {
            return Err(ctx.error(
                &shape_span,
                &key("axis"),
                "is required by a cylinder, cone or pyramid wall".into(),
            ))
        }
        (Some(a), Kind::Ball) if w.spin.is_some() && D == 3 => non_zero(a, "axis")?,
        // A 3D box turns with its normal and its axis together; its edges are the coordinate
        // axes with neither.
        (Some(a), Kind::Box) if D == 3 && w.normal.is_some() => non_zero(a, "axis")?,
        (None, Kind::Box) if D == 3 && w.normal.is_none() => {
            let mut first = Vector::<D>::zeros();
            first[0] = 1.0;
            first
        }
        (_, Kind::Box) if D == 3 => {
            let (span, field) = match (&w.axis, &w.normal) {
                (Some(a), _) => (a.span(), "axis"),
                (None, Some(n)) => (n.span(), "normal"),
                (None, None) => (shape_span.clone(), "normal"),
            };
            return Err(ctx.error(
                &span,
                &key(field),
                "a 3D box is turned by its `normal` and its `axis` (the direction of its first edge) together: give both, or neither for a box with its edges along x, y, z".into(),
            ));
        }
        (Some(a), _) => {
            return refuse(
                a.span(),
                "axis",
                "only a cylinder, cone or pyramid wall, a box in 3D or a spinning ball in 3D has an axis",
            )
        }
        (None, _) => Vector::<D>::zeros(),
    };
    let length = match (&w.length, kind) {
        (Some(l), Kind::Cylinder) => Some(ctx.positive(l, &key("length"))?),
        (Some(l), _) => return refuse(l.span(), "length", "only a cylinder wall has a length"),
        (None, _) => None,
    };
    let size = match (&w.size, kind) {
        (Some(s), Kind::Box) => {
            let size = ctx.vector::<D>(s, &key("size"))?;
            if let Some(a) = size.iter().find(|a| !(a.is_finite() && **a > 0.0)) {
                return Err(ctx.error(
                    &s.span(),
                    &key("size"),
                    format!("a box's edge lengths must be finite numbers > 0, got {a}"),
                ));
            }
            size
        }
        (None, Kind::Box) => {
            return refuse(
                shape_span,
                "size",
                "is required by a box wall (its edge lengths)",
            )
        }
        (Some(s), _) => {
            return refuse(
                s.span(),
                "size",
                "only a box wall has a size (a disc, ball or cylinder has a `radius`)",
            )
        }
        (None, _) => Vector::<D>::zeros(),
    };
    let edge_radius = match (&w.edge_radius, kind) {
        (Some(r), Kind::Box) => {
            let radius = *r.get_ref();
            let half_shortest = 0.5 * size.min();
            if !(radius.is_finite() && radius >= 0.0 && radius <= half_shortest) {
                return refuse(
                    r.span(),
                    "edge_radius",
                    &format!("must be a finite number ≥ 0 and at most half the box's shortest edge, {half_shortest:e}, got {radius}"),
                );
            }
            radius
        }
        (Some(r), _) => {
            return refuse(
                r.span(),
                "edge_radius",
                "only a box wall has an edge radius",
            )
        }
        (None, _) => 0.0,
    };
    let half_angle = match (&w.half_angle, kind) {
        (Some(a), Kind::Cone | Kind::Pyramid) => {
            let degrees = *a.get_ref();
            if !(degrees > 0.0 && degrees < 90.0) {
                return refuse(
                    a.span(),
                    "half_angle",
                    &format!("must be an angle in degrees between 0 and 90 (exclusive), got {degrees}"),
                );
            }
            degrees.to_radians()
        }
        (None, Kind::Cone) => {
            return refuse(
                shape_span,
                "half_angle",
                "is required by a cone wall: the angle between its axis and its flanks, in degrees (60 for a Rockwell cone)",
            )
        }
        (None, Kind::Pyramid) => {
            return refuse(
                shape_span,
                "half_angle",
                "is required by a pyramid wall: the angle between its axis and each face's centre line, in degrees (68 for a Vickers pyramid, 65.27 for a Berkovich)",
            )
        }
        (Some(a), _) => {
            return refuse(
                a.span(),
                "half_angle",
                "only a cone or pyramid wall has a half-angle",
            )
        }
        (None, _) => 0.0,
    };
    let tip_radius =
        match (&w.tip_radius, kind) {
            (Some(r), Kind::Cone | Kind::Pyramid) => ctx.non_negative(r, &key("tip_radius"))?,
            (Some(r), _) => return refuse(
                r.span(),
                "tip_radius",
                "only a cone or pyramid wall has a tip radius (a box's edges are rounded by `edge_radius`)",
            ),
            (None, _) => 0.0,
        };
    let sides = match (&w.sides, kind) {
        (Some(n), Kind::Pyramid) => {
            let count = *n.get_ref();
            if !(3..=MAX_PYRAMID_SIDES).contains(&count) {
                return refuse(
                    n.span(),
                    "sides",
                    &format!("must be a whole number of faces from 3 to {MAX_PYRAMID_SIDES}, got {count} (a pyramid of many more faces is nearly a cone: shape = \"cone\")"),
                );
            }
            count as usize
        }
        (None, Kind::Pyramid) => {
            return refuse(
                shape_span,
                "sides",
                "is required by a pyramid wall: its number of faces (4 for a Vickers pyramid, 3 for a Berkovich)",
            )
        }
        (Some(n), _) => return refuse(n.span(), "sides", "only a pyramid wall has sides"),
        (None, _) => 0,
    };
    let face_direction = match (&w.face_direction, kind) {
        (Some(f), Kind::Pyramid) => non_zero(f, "face_direction")?,
        (None, Kind::Pyramid) => {
            return refuse(
                shape_span,
                "face_direction",
                "is required by a pyramid wall: the direction, at right angles to its axis, from the axis towards the middle of its first face",
            )
        }
        (Some(f), _) => {
            return refuse(
                f.span(),
                "face_direction",
                "only a pyramid wall has a face direction",
            )
        }
        (None, _) => Vector::<D>::zeros(),
    };
    let shape = match kind {
        Kind::Plane => WallShape::Plane,
        Kind::Disc => WallShape::Disc { radius },
        // A ball's axis (3D, spinning) is only the spin's: the shape has none.
        Kind::Ball => WallShape::Ball { radius },
        Kind::Cylinder => WallShape::Cylinder {
            radius,
            axis,
            length,
        },
        Kind::Box => WallShape::Box {
            size,
            axis,
            edge_radius,
        },
        Kind::Cone => WallShape::Cone {
            axis,
            half_angle,
            tip_radius,
        },
        Kind::Pyramid => WallShape::Pyramid {
            axis,
            face_direction,
            sides,
            half_angle,
            tip_radius,
        },
    };
    if let Some(Err(why)) = shape.rigid_pyramid(Vector::<D>::zeros(), (&[], &[], &[])) {
        let span = w.face_direction.as_ref().map_or(shape_span, |f| f.span());
        return Err(ctx.error(&span, &key("face_direction"), why));
    }
    if let Some(Err(why)) = shape.box_frame(normal) {
        let span = w.axis.as_ref().map_or(shape_span, |a| a.span());
        return Err(ctx.error(&span, &key("axis"), why));
    }
    Ok((shape, normal))
}

/// The wall's angular velocity from `spin` (ω about the wall's own axis, right-handed): along
/// a plane's or a disc's normal, a cylinder's or a cone's axis or a 3D ball's `axis`, along z
/// for a 2D ball. A spin is felt only through friction, and is its own mirror image only about a
/// symmetry plane's normal.
#[allow(clippy::too_many_arguments)]
fn wall_spin<const D: usize>(
    ctx: &Context<'_>,
    w: &WallTable,
    spin: &toml::Spanned<f64>,
    shape: &WallShape<D>,
    unit: Vector<D>,
    friction: &tlsph_solver::FrictionCoefficients,
    symmetry_planes: &[SymmetryPlaneTable],
    key: &dyn Fn(&str) -> String,
) -> Result<Vector3, SceneError> {
    let omega = *spin.get_ref();
    let refuse = |message: String| Err(ctx.error(&spin.span(), &key("spin"), message));
    if !omega.is_finite() {
        return refuse(format!("must be a finite number, got {omega}"));
    }
    if !friction.is_frictional() {
        return refuse(
            "a spin is felt only through friction; give `friction` (or `static_friction`), or drop `spin`"
                .into(),
        );
    }
    // The shape's own axis; a ball in 3D spins about the `axis` given.
    let axis = match (shape.spin_axis(unit), &w.axis) {
        (Err(why), _) => return refuse(why),
        (Ok(Some(axis)), _) => axis,
        (Ok(None), Some(a)) => vector_to_3d(&ctx.vector::<D>(a, &key("axis"))?).normalize(),
        (Ok(None), None) => {
            return refuse("a spinning ball in 3D needs an `axis` to spin about".into())
        }
    };
    // A rotation about an axis normal to a mirror is its own mirror image; about any other
    // axis the mirrored half would turn the other way.
    for plane in symmetry_planes {
        let Some(a) = axis_index(plane.axis.get_ref()).filter(|&a| a < D) else {
            continue;
        };
        if axis[a].abs() != 1.0 {
            return refuse(format!(
                "the wall spins about {}, not about the normal of the symmetry plane {} = {}: the mirrored half would spin the other way, so the model is not symmetric",
                point_text(&axis),
                plane.axis.get_ref(),
                plane.position.get_ref()
            ));
        }
    }
    Ok(axis * omega)
}

/// No particle may start inside a ball, a cylinder, a box, a cone or a pyramid, nor behind a
/// plane or a disc's face.
fn check_start<const D: usize>(
    ctx: &Context<'_>,
    w: &WallTable,
    shape: &WallShape<D>,
    point: Vector<D>,
    unit: Vector<D>,
    bodies: &[BodyDescription<D>],
    key: &dyn Fn(&str) -> String,
) -> Result<(), SceneError> {
    // Distance from the ball's centre or the cylinder's axis.
    let inside = |what: &str, r: f64, distance: &dyn Fn(&Vector<D>) -> f64| {
        for body in bodies {
            if let Some(x) = body.positions.iter().find(|x| distance(x) < r) {
                return Err(ctx.error(
                    &w.point.span(),
                    &key("point"),
                    format!(
                        "body `{}` starts inside the {what}: its particle at [{}] is {:.3e} from the {}, less than the radius {r:e}",
                        body.name,
                        point_text(x),
                        distance(x),
                        if what == "ball" { "centre" } else { "axis" },
                    ),
                ));
            }
        }
        Ok(())
    };
    let disc_radius = match *shape {
        WallShape::Ball { radius } => return inside("ball", radius, &|x| (x - point).norm()),
        WallShape::Cylinder {
            radius,
            axis,
            length,
        } => {
            // A finite cylinder: only a particle within its length can be inside.
            let axis = axis / axis.norm();
            let half_length = length.map_or(f64::INFINITY, |l| 0.5 * l);
            return inside("cylinder", radius, &|x| {
                let offset = x - point;
                if offset.dot(&axis).abs() < half_length {
                    across(&offset, &axis).norm()
                } else {
                    f64::INFINITY
                }
            });
        }
        WallShape::Box { size, .. } => {
            // Checked when the shape was read; a box without a frame has no inside.
            let Some(Ok(block)) = shape.rigid_box(point, unit, (&[], &[], &[])) else {
                return Ok(());
            };
            return match first_inside(bodies, |x| block.distance(x).0) {
                Some((body, x, depth)) => Err(ctx.error(
                    &w.point.span(),
                    &key("point"),
                    format!(
                        "body `{body}` starts inside the box: its particle at [{}] is {depth:.3e} inside the surface of the box of edges [{}] about its centre",
                        point_text(&x),
                        point_text(&size),
                    ),
                )),
                None => Ok(()),
            };
        }
        WallShape::Cone { .. } => {
            // Checked when the shape was read.
            let Some(Ok(cone)) = shape.rigid_cone(point, (&[], &[], &[])) else {
                return Ok(());
            };
            return match first_inside(bodies, |x| cone.distance(x).0) {
                Some((body, x, depth)) => Err(ctx.error(
                    &w.point.span(),
                    &key("point"),
                    format!(
                        "body `{body}` starts inside the cone: its particle at [{}] is {depth:.3e} inside its surface (`point` is the cone's tip, `axis` points from the tip into it)",
                        point_text(&x),
                    ),
                )),
                None => Ok(()),
            };
        }
        WallShape::Pyramid { .. } => {
            // Checked when the shape was read.
            let Some(Ok(pyramid)) = shape.rigid_pyramid(point, (&[], &[], &[])) else {
                return Ok(());
            };
            return match first_inside(bodies, |x| pyramid.distance(x).0) {
                Some((body, x, depth)) => Err(ctx.error(
                    &w.point.span(),
                    &key("point"),
                    format!(
                        "body `{body}` starts inside the pyramid: its particle at [{}] is {depth:.3e} inside its surface (`point` is the pyramid's tip, `axis` points from the tip into it)",
                        point_text(&x),
                    ),
                )),
                None => Ok(()),
            };
        }
        WallShape::Plane => None,
        WallShape::Disc { radius } => Some(radius),
    };
    // Of a finite wall only what lies in front of or behind its face can be on the wrong
    // side; beyond its rim a body may be anywhere.
    let in_footprint =
        |x: &Vector<D>| disc_radius.is_none_or(|r| across(&(x - point), &unit).norm() <= r);
    for body in bodies {
        let behind = body
            .positions
            .iter()
            .filter(|x| in_footprint(x))
            .map(|x| (x, (x - point).dot(&unit)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((x, d)) = behind.filter(|(_, d)| *d < 0.0) {
            let face = if disc_radius.is_some() {
                "disc"
            } else {
                "plane"
            };
            return Err(ctx.error(
                &w.point.span(),
                &key("point"),
                format!(
                    "body `{}` starts behind the wall: its particle at [{}] is {:.3e} on the far side of the {face} (particles must start on the side the normal points to)",
                    body.name,
                    point_text(x),
                    -d
                ),
            ));
        }
    }
    Ok(())
}

/// The first particle (of the first body that has one) inside a solid wall whose signed
/// distance (negative inside) is `distance`: its body's name, its position and its depth.
fn first_inside<const D: usize>(
    bodies: &[BodyDescription<D>],
    distance: impl Fn(Vector<D>) -> f64,
) -> Option<(&str, Vector<D>, f64)> {
    bodies.iter().find_map(|body| {
        body.positions.iter().find_map(|x| {
            let s = distance(*x);
            (s < 0.0).then(|| (body.name.as_str(), *x, -s))
        })
    })
}

/// The mirrored half of a model meets the wall's mirror image. A finite wall crossing a
/// symmetry plane must be its own mirror image: a disc (whose face lies across the plane), a
/// ball, a cylinder lying along the plane or a box with a face parallel to it, centred on it
/// and not moving across it; a cylinder along the plane's normal always is (its sliding is
/// checked with the velocity); an oblique cylinder or a box turned askew to it never.
#[allow(clippy::too_many_arguments)]
fn check_symmetry<const D: usize>(
    ctx: &Context<'_>,
    w: &WallTable,
    shape: &WallShape<D>,
    point: Vector<D>,
    unit: Vector<D>,
    sliding: impl Fn(usize) -> bool,
    symmetry_planes: &[SymmetryPlaneTable],
    key: &dyn Fn(&str) -> String,
) -> Result<(), SceneError> {
    if let WallShape::Cone {
        axis,
        half_angle,
        tip_radius,
    } = *shape
    {
        let cone = (axis / axis.norm(), half_angle, tip_radius);
        let tip = TipShape::Cone;
        return check_tip_symmetry(ctx, w, tip, cone, point, sliding, symmetry_planes, key);
    }
    if let WallShape::Pyramid {
        axis, tip_radius, ..
    } = *shape
    {
        // Checked when the shape was read.
        let Some(Ok(pyramid)) = shape.rigid_pyramid(point, (&[], &[], &[])) else {
            return Ok(());
        };
        let tip = TipShape::Pyramid {
            face_normals: pyramid.face_normals().to_vec(),
            edges: pyramid.edges().to_vec(),
        };
        let held = (axis / axis.norm(), 0.0, tip_radius);
        return check_tip_symmetry(ctx, w, tip, held, point, sliding, symmetry_planes, key);
    }
    // Only a finite shape (which has a radius or a size) can cross a plane.
    let (finite_span, finite_field) = match (&w.radius, &w.size) {
        (Some(r), _) => (r.span(), "radius"),
        (None, Some(s)) => (s.span(), "size"),
        (None, None) => return Ok(()),
    };
    for plane in symmetry_planes {
        let Some(a) = axis_index(plane.axis.get_ref()).filter(|&a| a < D) else {
            continue;
        };
        let position = *plane.position.get_ref();
        let off_centre =
            |r: f64| (point[a] - position).abs() < r && (point[a] != position || sliding(a));
        let (what, problem) = match *shape {
            WallShape::Plane | WallShape::Cone { .. } | WallShape::Pyramid { .. } => continue,
            WallShape::Disc { radius } => ("disc", unit[a] == 0.0 && off_centre(radius)),
            WallShape::Ball { radius } => ("ball", off_centre(radius)),
            WallShape::Cylinder {
                radius,
                axis,
                length,
            } => {
                let along = axis[a].abs() / axis.norm();
                if along == 1.0 {
                    // Along the normal: unbounded, it is its own mirror image; of finite
                    // length, it reaches L/2 to either side of its point.
                    match length {
                        None => continue,
                        Some(length) => ("cylinder", off_centre(0.5 * length)),
                    }
                } else {
                    // How far an oblique cylinder reaches along the normal: unbounded, without
                    // end; of finite length, ½L cos θ + R sin θ.
                    let reach = length.map_or(f64::INFINITY, |l| {
                        0.5 * l * along + radius * (1.0 - along * along).sqrt()
                    });
                    if along > 0.0 && (point[a] - position).abs() < reach {
                        let axis_span = w.axis.as_ref().map_or(finite_span, |a| a.span());
                        return Err(ctx.error(
                            &axis_span,
                            &key("axis"),
                            format!(
                                "the cylinder's axis is oblique to the symmetry plane {} = {}, so it crosses the plane and its mirror image is another cylinder; lay the axis along the plane or along its normal{}",
                                plane.axis.get_ref(),
                                position,
                                if length.is_some() { ", or keep it clear of the plane" } else { "" }
                            ),
                        ));
                    }
                    ("cylinder", along == 0.0 && off_centre(radius))
                }
            }
            WallShape::Box {
                size, edge_radius, ..
            } => {
                // Checked when the shape was read.
                let Some(Ok(frame)) = shape.box_frame(unit) else {
                    continue;
                };
                // How far the box reaches along the normal: Σ (a_k/2 − ρ) |e_k·n| + ρ.
                let reach: f64 = (0..D)
                    .map(|k| (0.5 * size[k] - edge_radius) * frame[(a, k)].abs())
                    .sum::<f64>()
                    + edge_radius;
                let faces_the_plane = (0..D).any(|k| frame[(a, k)].abs() == 1.0);
                if !faces_the_plane && (point[a] - position).abs() < reach {
                    let span = w.normal.as_ref().map_or(finite_span, |n| n.span());
                    return Err(ctx.error(
                        &span,
                        &key("normal"),
                        format!(
                            "the box is turned so that none of its faces is parallel to the symmetry plane {} = {}, and it crosses the plane, so its mirror image is another box; turn it so that a face is parallel to the plane, or keep it clear of the plane",
                            plane.axis.get_ref(),
                            position,
                        ),
                    ));
                }
                ("box", off_centre(reach))
            }
        };
        if problem {
            return Err(ctx.error(
                &finite_span,
                &key(finite_field),
                format!(
                    "the {what} crosses the symmetry plane {} = {position} off its centre or moves across it, so the model's mirrored half would meet another wall; centre the {what} on the plane and move it along the plane only, or keep it clear of the plane",
                    plane.axis.get_ref(),
                ),
            ));
        }
    }
    Ok(())
}

/// A pointed wall unbounded towards its base, as [`check_tip_symmetry`] sees it.
enum TipShape<const D: usize> {
    Cone,
    /// A pyramid's faces' outward unit normals and its edges' directions from the apex.
    Pyramid {
        face_normals: Vec<Vector<D>>,
        edges: Vec<Vector<D>>,
    },
}

impl<const D: usize> TipShape<D> {
    fn name(&self) -> &'static str {
        match self {
            TipShape::Cone => "cone",
            TipShape::Pyramid { .. } => "pyramid",
        }
    }

    /// Whether the mirror of unit normal `m` through the axis maps the shape onto itself:
    /// always for a cone; for a pyramid when it maps the set of its faces' normals onto itself
    /// (each reflected normal n̂ − 2(n̂·m)m within 1e-9 of one of them), that is when the
    /// mirror passes through the middle of a face or an edge.
    fn mirrored_by(&self, m: &Vector<D>) -> bool {
        match self {
            TipShape::Cone => true,
            TipShape::Pyramid { face_normals, .. } => face_normals.iter().all(|n| {
                let image = n - m * (2.0 * n.dot(m));
                face_normals.iter().any(|k| (image - k).norm() <= 1e-9)
            }),
        }
    }

    /// Whether the shape, with its unit axis at the angle θ to the unit normal `m` of a plane
    /// and its half-angle α (a cone's), leans back towards the plane: a cone when θ + α > 90°,
    /// a pyramid when one of its edges points towards the plane. `away` (±1) is the side of the
    /// plane the axis points to.
    fn leans_towards(
        &self,
        m: &Vector<D>,
        away: f64,
        (axis, half_angle): (Vector<D>, f64),
    ) -> bool {
        match self {
            TipShape::Cone => {
                let theta = axis.dot(m).abs().min(1.0).acos();
                theta + half_angle > std::f64::consts::FRAC_PI_2
            }
            TipShape::Pyramid { edges, .. } => edges.iter().any(|e| away * e.dot(m) < 0.0),
        }
    }
}

/// A cone or a pyramid is unbounded towards its base, so it crosses every symmetry plane that
/// its axis does not point away from steeply enough. It is its own mirror image when its axis
/// lies along the plane, its tip on it, it does not move across it, and (a pyramid) the plane
/// passes through the middle of a face or an edge; otherwise it must stay clear of the plane:
/// pointing away from it without leaning back towards it (a cone's axis at an angle θ to the
/// plane's normal with θ + α ≤ 90°; every edge of a pyramid pointing away), and its rounded
/// tip, the sphere of radius ρ about tip + ρ â, not reaching it. `half_angle` is a cone's α
/// (not read for a pyramid).
#[allow(clippy::too_many_arguments)]
fn check_tip_symmetry<const D: usize>(
    ctx: &Context<'_>,
    w: &WallTable,
    tip: TipShape<D>,
    (axis, half_angle, tip_radius): (Vector<D>, f64, f64),
    point: Vector<D>,
    sliding: impl Fn(usize) -> bool,
    symmetry_planes: &[SymmetryPlaneTable],
    key: &dyn Fn(&str) -> String,
) -> Result<(), SceneError> {
    let what = tip.name();
    let span = w.axis.as_ref().map_or(w.point.span(), |a| a.span());
    for plane in symmetry_planes {
        let Some(a) = axis_index(plane.axis.get_ref()).filter(|&a| a < D) else {
            continue;
        };
        let position = *plane.position.get_ref();
        let where_ = format!("the symmetry plane {} = {position}", plane.axis.get_ref());
        let (problem, field) = if axis[a] == 0.0 {
            let mut normal = Vector::<D>::zeros();
            normal[a] = 1.0;
            if point[a] != position || sliding(a) {
                (format!("the {what}'s axis lies along {where_} but its tip is off the plane or it moves across it, so the model's mirrored half would meet another {what}; put its tip on the plane and move it along the plane only"), "axis")
            } else if !tip.mirrored_by(&normal) {
                (format!("the pyramid's axis lies along {where_} but the plane passes through neither the middle of a face nor an edge, so its mirror image is another pyramid; turn `face_direction` so that it does (e.g. along the plane or along its normal for 4 sides, along the plane for 3)"), "face_direction")
            } else {
                continue;
            }
        } else {
            let away = axis[a].signum();
            let mut normal = Vector::<D>::zeros();
            normal[a] = 1.0;
            let tip_centre = point[a] + axis[a] * tip_radius;
            if !tip.leans_towards(&normal, away, (axis, half_angle))
                && away * (tip_centre - position) >= tip_radius
            {
                continue;
            }
            let steeply = match tip {
                TipShape::Cone => "its axis within 90° − half_angle of the plane's normal",
                TipShape::Pyramid { .. } => "every edge pointing away from the plane",
            };
            (format!("the {what} reaches across {where_} (it is unbounded towards its base), so its mirror image is another {what}; lay its axis along the plane with its tip on it, or point it away from the plane steeply enough ({steeply}) with its tip clear of the plane"), "axis")
        };
        let span = match (field, &w.face_direction) {
            ("face_direction", Some(f)) => f.span(),
            _ => span.clone(),
        };
        return Err(ctx.error(&span, &key(field), problem));
    }
    Ok(())
}
