//! Contact at a symmetry plane (numerics.md §12–13.1): a ball dropped on a plate, modelled
//! whole and as a half (2D) or quarter (3D) with symmetry planes through its axis. The
//! contact of the particles next to a plane must see the mirror images of the other body's
//! particles beyond it, so the reduced model moves like the full one, for the potential law
//! (total- and updated-Lagrangian) and the penalty law with friction; and a body in
//! self-contact (either law) strikes its own image as the full model's two halves strike each
//! other.

use super::contact::{body, config, materials};
use tlsph_math::Vector;
use tlsph_solver::{
    ContactDescription, EffectsDescription, Formulation, FrictionCoefficients, Model,
    PenaltyContactDescription, Simulation, SymmetryPlane,
};

/// Spacing of both bodies.
const DX: f64 = 0.05;
/// Downward speed of the ball (c = 1 in the lighter material).
const SPEED: f64 = 0.05;

/// Cell-centred lattice points of the box [−n_a Δx, n_a Δx] along every axis but the last,
/// and [lo, hi) cells along the last: symmetric about every coordinate plane x_a = 0, a < D−1.
fn centred_box<const D: usize>(half_cells: usize, lo: i64, hi: i64) -> Vec<Vector<D>> {
    let n = 2 * half_cells as i64;
    let lateral = n.pow(D as u32 - 1);
    let mut out = Vec::new();
    for k in 0..lateral {
        for z in lo..hi {
            let mut x = Vector::<D>::zeros();
            let mut rest = k;
            for a in 0..D - 1 {
                x[a] = ((rest % n) as f64 - half_cells as f64 + 0.5) * DX;
                rest /= n;
            }
            x[D - 1] = (z as f64 + 0.5) * DX;
            out.push(x);
        }
    }
    out
}

/// The full model: a ball of radius `radius` (lattice points of a box within it) whose lowest
/// particle starts 1.05 Δx above the plate's top row (the potential law's d0 and the penalty
/// range are Δx), falling at [`SPEED`] on a plate of (2 `plate_cells` Δx)^(D−1) × 4Δx.
fn ball_on_plate<const D: usize>(
    radius_cells: usize,
    plate_cells: usize,
    formulation: Formulation,
    end_time: f64,
    effects: EffectsDescription<D>,
) -> Model<D> {
    let radius = radius_cells as f64 * DX;
    let r = radius_cells as i64;
    let mut ball: Vec<Vector<D>> = centred_box::<D>(radius_cells, -r, r)
        .into_iter()
        .filter(|x| x.norm() <= radius)
        .collect();
    let lowest = ball.iter().map(|x| x[D - 1]).fold(f64::INFINITY, f64::min);
    for x in &mut ball {
        x[D - 1] += 1.05 * DX - lowest;
    }
    let plate = centred_box::<D>(plate_cells, -4, 0)
        .into_iter()
        .map(|mut x| {
            x[D - 1] -= 0.5 * DX;
            x
        })
        .collect();
    let mut down = Vector::<D>::zeros();
    down[D - 1] = -SPEED;
    Model {
        config: config(formulation, end_time),
        materials: materials(),
        bodies: vec![
            body("ball", 0, ball, DX, down),
            body("plate", 1, plate, DX, Vector::<D>::zeros()),
        ],
        boundaries: vec![],
        effects,
    }
}

/// The reduced model: the particles with x_a > 0 for every lateral axis a, and the planes
/// x_a = 0.
fn reduced<const D: usize>(full: &Model<D>) -> Model<D> {
    let mut part = full.clone();
    for b in &mut part.bodies {
        let keep: Vec<bool> = b
            .positions
            .iter()
            .map(|x| (0..D - 1).all(|a| x[a] > 0.0))
            .collect();
        let mut k = 0;
        b.positions.retain(|_| (keep[k], k += 1).0);
        k = 0;
        b.volumes.retain(|_| (keep[k], k += 1).0);
        k = 0;
        b.velocities.retain(|_| (keep[k], k += 1).0);
    }
    part.effects.symmetry_planes = (0..D - 1)
        .map(|axis| SymmetryPlane {
            axis,
            position: 0.0,
        })
        .collect();
    part
}

/// Runs the full and the reduced model side by side and checks, every step, that the
/// reduced model's contact force along the fall is the full one's divided by the number of
/// copies, as are the booked contact energy and the total energy, and at the end that every
/// particle of the reduced model moved as its twin in the full model.
/// Returns the largest relative force mismatch and the peak contact force of the full model.
fn compare<const D: usize>(full: Model<D>, label: &str) -> (f64, f64) {
    let copies = (1usize << (D - 1)) as f64;
    let part = reduced(&full);
    let twin: Vec<usize> = part
        .bodies
        .iter()
        .flat_map(|b| &b.positions)
        .map(|x| {
            full.bodies
                .iter()
                .flat_map(|b| &b.positions)
                .position(|y| y == x)
                .unwrap()
        })
        .collect();
    let mut a = Simulation::new(full).unwrap();
    let mut b = Simulation::new(part).unwrap();
    let booked = |d: &tlsph_solver::Diagnostics| {
        d.effect_energies
            .iter()
            .find(|(name, _)| name == "contact")
            .map_or(f64::NAN, |(_, e)| *e)
    };
    let (mut worst, mut peak) = (0.0f64, 0.0f64);
    let (mut worst_energy, mut peak_energy) = (0.0f64, 0.0f64);
    while !a.finished() {
        a.step().unwrap();
        b.step().unwrap();
        let (da, db) = (a.diagnostics(), b.diagnostics());
        // Along the fall (the reduced ball's lateral resultant is balanced by the images).
        let (fa, fb) = (
            da.effect_force("contact")[D - 1],
            db.effect_force("contact")[D - 1],
        );
        peak = peak.max(fa.abs());
        worst = worst.max((fa - fb * copies).abs());
        // The contact's booked energy (stored or worked) and the total are the full model's
        // shares.
        peak_energy = peak_energy.max(booked(&da).abs());
        worst_energy = worst_energy
            .max((booked(&da) - copies * booked(&db)).abs())
            .max((da.total_energy() - copies * db.total_energy()).abs());
    }
    assert!(b.finished(), "{label}: both models take the same steps");
    assert!(peak_energy > 0.0, "{label}: the contact booked no energy");
    assert!(
        worst_energy <= 1e-9 * peak_energy,
        "{label}: contact or total energy of the reduced model × {copies} differs from the full one by {worst_energy:e} (peak contact energy {peak_energy:e})"
    );
    // The ball has come to the plate and bounced: the full model's contact did work.
    let v_ball = |s: &Simulation<D>| {
        let range = s.bodies()[0].range.clone();
        let m: f64 = range.clone().map(|i| s.masses()[i]).sum();
        range
            .map(|i| s.velocity(i) * s.masses()[i])
            .sum::<Vector<D>>()
            / m
    };
    let (va, vb) = (v_ball(&a), v_ball(&b));
    assert!(
        va[D - 1] > -0.5 * SPEED,
        "{label}: the full model's ball has been stopped by the contact ({va})"
    );
    assert!(
        (va[D - 1] - vb[D - 1]).abs() <= 1e-9 * SPEED,
        "{label}: ball velocity {} (reduced) vs {} (full)",
        vb[D - 1],
        va[D - 1]
    );
    let scale = (0..a.n_particles())
        .map(|i| a.total_displacement(i).norm())
        .fold(0.0, f64::max);
    for (k, &i) in twin.iter().enumerate() {
        let diff = (a.total_displacement(i) - b.total_displacement(k)).norm();
        assert!(
            diff <= 1e-9 * scale,
            "{label}: particle {k} of the reduced model is {diff:e} from its twin (scale {scale:e})"
        );
    }
    (worst / peak, peak)
}

fn potential() -> Option<ContactDescription> {
    Some(ContactDescription {
        scale: 1.0,
        exponent: 4.0,
        pairs: None,
    })
}

#[test]
fn a_half_model_in_contact_at_its_plane_moves_like_the_full_model() {
    // The ball's column on the plane presses on the plate's column there. Without the
    // images beyond the plane (before they were added) the half model's contact force along
    // the fall was off by 6 % of its peak; with them it agrees to round-off (9e-14 to 1.4e-12
    // of the peak).
    for (formulation, effects, label) in [
        (
            Formulation::TotalLagrangianCorrected,
            EffectsDescription {
                contact: potential(),
                ..Default::default()
            },
            "potential, TL",
        ),
        (
            Formulation::UpdatedLagrangian,
            EffectsDescription {
                contact: potential(),
                ..Default::default()
            },
            "potential, UL",
        ),
        (
            Formulation::TotalLagrangianCorrected,
            EffectsDescription {
                penalty_contact: Some(PenaltyContactDescription {
                    stiffness: 1.0,
                    range: 1.0,
                    friction: FrictionCoefficients::single(0.3),
                    pairs: None,
                }),
                ..Default::default()
            },
            "penalty with friction, TL",
        ),
        (
            Formulation::UpdatedLagrangian,
            EffectsDescription {
                penalty_contact: Some(PenaltyContactDescription {
                    stiffness: 1.0,
                    range: 1.0,
                    friction: FrictionCoefficients::single(0.3),
                    pairs: None,
                }),
                ..Default::default()
            },
            "penalty with friction, UL",
        ),
    ] {
        let full = ball_on_plate::<2>(7, 20, formulation, 4.0, effects);
        let (mismatch, peak) = compare(full, label);
        assert!(peak > 0.0, "{label}: no contact");
        eprintln!("{label}: force mismatch {mismatch:e} of the peak {peak:e}");
    }
}

#[test]
fn a_quarter_model_in_contact_at_its_planes_moves_like_the_full_model() {
    // Two planes: the particles on the ball's axis meet the corner images too. Without the
    // images the quarter model's contact force was off by as much as its peak.
    let full = ball_on_plate::<3>(
        4,
        8,
        Formulation::TotalLagrangianCorrected,
        10.0,
        EffectsDescription {
            contact: potential(),
            ..Default::default()
        },
    );
    let (mismatch, peak) = compare(full, "potential, TL, 3D");
    eprintln!("3D: force mismatch {mismatch:e} of the peak {peak:e}");
}

#[test]
fn a_body_in_self_contact_meets_its_own_mirror_image_as_the_full_model_meets_its_other_half() {
    // Full model: one body of two blocks, 4Δx apart across x = 0 (no reference bond joins
    // them), closing at ±0.03 in self-contact, of either law. Half model: the right block
    // alone with the plane x = 0, which it strikes as its own image (the image pair's
    // reference distance is beyond the support, so self-contact accepts it). (Friction, declared
    // for the penalty law, has nothing to do: the two halves of a mirror-symmetric motion do
    // not slide along the plane.)
    let potential = EffectsDescription {
        contact: Some(ContactDescription {
            scale: 0.5,
            exponent: 4.0,
            pairs: Some(vec![(0, 0)]),
        }),
        ..Default::default()
    };
    let penalty = EffectsDescription {
        penalty_contact: Some(PenaltyContactDescription {
            stiffness: 1.0,
            range: 1.0,
            friction: FrictionCoefficients::single(0.3),
            pairs: Some(vec![(0, 0)]),
        }),
        ..Default::default()
    };
    for effects in [potential, penalty] {
        self_contact_at_the_plane(effects);
    }
}

/// The half and full models of the test above, with the contact of `effects`.
fn self_contact_at_the_plane(effects: EffectsDescription<2>) {
    let block: Vec<Vector<2>> = super::lattice([8, 6], DX)
        .iter()
        .map(|x| x + Vector::<2>::new(1.5 * DX, 0.0))
        .collect();
    let mirrored: Vec<Vector<2>> = block
        .iter()
        .map(|x| Vector::<2>::new(-x[0], x[1]))
        .collect();
    let velocities: Vec<Vector<2>> = block
        .iter()
        .map(|_| Vector::<2>::new(-0.03, 0.0))
        .chain(block.iter().map(|_| Vector::<2>::new(0.03, 0.0)))
        .collect();
    let mut both = body(
        "both",
        0,
        [block.clone(), mirrored].concat(),
        DX,
        Vector::<2>::zeros(),
    );
    both.velocities = velocities;
    let full = Model {
        config: config(Formulation::TotalLagrangianCorrected, 4.0),
        materials: materials(),
        bodies: vec![both],
        boundaries: vec![],
        effects,
    };
    let mut half = full.clone();
    half.bodies[0].positions.truncate(block.len());
    half.bodies[0].volumes.truncate(block.len());
    half.bodies[0].velocities.truncate(block.len());
    half.effects.symmetry_planes = vec![SymmetryPlane {
        axis: 0,
        position: 0.0,
    }];
    let mut a = Simulation::new(full).unwrap();
    let mut b = Simulation::new(half).unwrap();
    a.run(|_, _| {}).unwrap();
    b.run(|_, _| {}).unwrap();
    assert_eq!(a.steps_done(), b.steps_done());
    let scale = (0..b.n_particles())
        .map(|i| a.total_displacement(i).norm())
        .fold(0.0, f64::max);
    for i in 0..b.n_particles() {
        let diff = (a.total_displacement(i) - b.total_displacement(i)).norm();
        assert!(
            diff <= 1e-9 * scale,
            "particle {i}: {diff:e} (scale {scale:e})"
        );
    }
    // It struck its image and rebounded (without the image it would fly through the plane).
    assert!(b.velocity(0)[0] > 0.0, "no rebound: {}", b.velocity(0));
}
