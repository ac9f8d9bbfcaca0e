//! Damaged elastic and elastic–plastic bodies (numerics.md §9.1–9.3): the solver's Peerlings
//! and Grady–Kipp wiring against the laws on homogeneous patches driven through a prescribed F(t), the
//! failure path, and determinism.
//!
//! Driving: with corrected gradients every particle of an affinely displaced patch sees the
//! exact F, so the whole patch is one material point. Its effective (undamaged) stress is the
//! Jaumann-rate integral Σ M Δf/f^{n−½}, which differs from M ln f (the Hencky strain the
//! damage law reads) by ε Δf²/12 summed over the path: 3·10⁻¹⁴ for the 3000 steps to
//! ε = 0.012 used below, so 1e-12 is a real check of the law, not of the time integration.

use super::{lattice, model, Setup};
use tlsph_materials::{GradyKipp, LinearElastic, PeerlingsSoftening, VonMisesPlasticity};
use tlsph_math::Vector;
use tlsph_solver::{
    DamageModel, ElasticDamage, ElasticPlastic, MaterialModel, Model, ParticleField, PressureModel,
    SetupError, Simulation, StrengthModel, StressUpdate,
};

const KAPPA0: f64 = 0.001;
const KAPPA_C: f64 = 0.01;

/// F-A13 unit law (problems.md F-A13 `[A]`): σ = Eε, E κ0 (κc − ε)/(κc − κ0), then 0.
fn peerlings_uniaxial(e: f64, strain: f64) -> f64 {
    if strain <= KAPPA0 {
        e * strain
    } else if strain < KAPPA_C {
        e * KAPPA0 * (KAPPA_C - strain) / (KAPPA_C - KAPPA0)
    } else {
        0.0
    }
}

/// Drives the 1D Peerlings patch of `sim` (particles at `positions`) in 3000 equal steps of F
/// to the Hencky strain 0.012 > κc, calling `check(step, ε, failed)` after each (`failed`: every
/// particle has failed), then asserts that both branches of the law were really visited
/// (> 2000 steps with κ0 < ε < κc, > 100 after failure) and every particle failed.
fn drive_past_failure(
    sim: &mut Simulation<1>,
    positions: &[Vector<1>],
    mut check: impl FnMut(&Simulation<1>, usize, f64, bool),
) {
    let mut f = 1.0;
    let (mut softening, mut failed) = (0, 0);
    for (k, next) in (1..).zip(driven_stretches()) {
        drive_to(sim, positions, f, next);
        f = next;
        let strain = f.ln();
        let all_failed = sim.failed_particles() == positions.len();
        check(sim, k, strain, all_failed);
        if strain > KAPPA0 && strain < KAPPA_C {
            softening += 1;
        }
        if all_failed {
            failed += 1;
            assert_eq!(sim.sample(ParticleField::Damage, 3), 1.0);
        }
    }
    assert!(softening > 2000, "{softening} softening steps");
    assert!(failed > 100, "{failed} steps after failure");
    assert_eq!(sim.failed_particles(), positions.len());
}

/// The stretches f of the 3000 steps of [`drive_past_failure`], to the Hencky strain 0.012.
fn driven_stretches() -> impl Iterator<Item = f64> {
    let steps = 3000;
    let target = 0.012f64.exp();
    (1..=steps).map(move |k| 1.0 + (target - 1.0) * k as f64 / steps as f64)
}

/// The Hencky strains ln f of [`driven_stretches`].
fn driven_strains() -> Vec<f64> {
    driven_stretches().map(f64::ln).collect()
}

fn damaged<const D: usize>(
    positions: Vec<Vector<D>>,
    dx: f64,
    elastic: LinearElastic,
    damage: DamageModel,
    end_time: f64,
) -> Model<D> {
    let material = MaterialModel::ElasticDamage(ElasticDamage { elastic, damage });
    with_material(positions, dx, material, end_time)
}

/// A body of `material` at rest on `positions`.
fn with_material<const D: usize>(
    positions: Vec<Vector<D>>,
    dx: f64,
    material: MaterialModel,
    end_time: f64,
) -> Model<D> {
    let mut m = model(
        positions,
        dx,
        |_| Vector::<D>::zeros(),
        Setup {
            end_time,
            ..Setup::default()
        },
    );
    m.materials[0].model = material;
    m
}

/// Drives `sim` so that its displacement becomes u = (f − 1) X_0 along x over one step of the
/// solver's own Δt (the velocity is chosen so that the drift lands there).
fn drive_to<const D: usize>(sim: &mut Simulation<D>, positions: &[Vector<D>], from: f64, to: f64) {
    let own = sim.next_dt();
    let u = |f: f64| -> Vec<Vector<D>> {
        positions
            .iter()
            .map(|x| {
                let mut u = Vector::<D>::zeros();
                u[0] = (f - 1.0) * x[0];
                u
            })
            .collect()
    };
    let (now, next) = (u(from), u(to));
    let v: Vec<Vector<D>> = now.iter().zip(&next).map(|(a, b)| (b - a) / own).collect();
    sim.set_displacements(&now);
    sim.set_velocities(&v);
    sim.step().unwrap();
}

#[test]
fn peerlings_patch_follows_the_uniaxial_law_through_the_solver() {
    // 1D (uniaxial strain) with ν = 0, so the longitudinal modulus M equals E and the patch
    // is Fuller's single particle in uniaxial tension (problems.md F-A13 unit test).
    let dx = 1.0;
    let positions = lattice([12], dx);
    let elastic = LinearElastic::new(1.0, 0.0).unwrap();
    let law = PeerlingsSoftening::new(KAPPA0, KAPPA_C).unwrap();
    let m = damaged(
        positions.clone(),
        dx,
        elastic,
        DamageModel::Peerlings(law),
        1e9,
    );
    let mut sim = Simulation::new(m).unwrap();
    assert!(sim.has_failure());
    sim.step().unwrap();
    drive_past_failure(&mut sim, &positions, |sim, k, strain, _| {
        let expected = peerlings_uniaxial(1.0, strain);
        for i in 0..positions.len() {
            let sigma = sim.stresses()[i][(0, 0)];
            assert!(
                (sigma - expected).abs() < 1e-12,
                "step {k}, ε = {strain}: σ = {sigma}, law {expected}"
            );
        }
    });
}

#[test]
fn peerlings_damage_does_not_heal_on_unloading() {
    // Load to ε = 0.005, unload to 0.003: the history κ keeps D(0.005), so σ = (1 − D)Eε
    // on the elastic unloading branch (numerics.md §9.1 `[C]`).
    let dx = 1.0;
    let positions = lattice([8], dx);
    let elastic = LinearElastic::new(1.0, 0.0).unwrap();
    let law = PeerlingsSoftening::new(KAPPA0, KAPPA_C).unwrap();
    let mut sim = Simulation::new(damaged(
        positions.clone(),
        dx,
        elastic,
        DamageModel::Peerlings(law),
        1e9,
    ))
    .unwrap();
    sim.step().unwrap();
    let (peak, back) = (0.005f64.exp(), 0.003f64.exp());
    let mut f = 1.0;
    for k in 1..=1000 {
        let next = 1.0 + (peak - 1.0) * k as f64 / 1000.0;
        drive_to(&mut sim, &positions, f, next);
        f = next;
    }
    for k in 1..=400 {
        let next = peak + (back - peak) * k as f64 / 400.0;
        drive_to(&mut sim, &positions, f, next);
        f = next;
    }
    let d = law.damage(0.005);
    let expected = (1.0 - d) * 0.003;
    assert!((sim.stresses()[4][(0, 0)] - expected).abs() < 1e-12);
    assert!((sim.sample(ParticleField::Damage, 4) - d).abs() < 1e-12);
}

/// Grady–Kipp patch set-up: 10 × 10 particles, Δx = 1, E = 1, ν = 0.3, ρ = 1; k chosen so that
/// the first flaw of the body activates at ε_1 = (1/(kV))^{1/m} = 1e-3.
const GK_M: f64 = 8.5;
fn gk_k(volume: f64) -> f64 {
    1e3f64.powf(GK_M) / volume
}

/// Drives a 10 × 10 Grady–Kipp patch (Δx = 1, ρ = 1, k of [`gk_k`], seed 7) made of
/// `material(law)` through plane-strain F = diag(f, 1) and checks D particle by particle
/// against the law: none below the first flaw, then Δ(D^{1/3}) = Δt n_act c_g/R_s up to the
/// cap n_act/n_i, and failure of every particle whose flaws are all active (numerics.md §9.2).
/// `effective(ε)` is the body's tensile driving strain σ1⁺(σ_eff)/E at Hencky strain ε = ln f,
/// and `strain_for` its inverse.
fn grady_kipp_patch_follows_the_law(
    material: impl Fn(DamageModel) -> MaterialModel,
    effective: impl Fn(f64) -> f64,
    strain_for: impl Fn(f64) -> f64,
) {
    let dx = 1.0;
    let positions = lattice([10, 10], dx);
    let n = positions.len();
    let volume = n as f64 * dx * dx;
    let gk = GradyKipp::new(GK_M, gk_k(volume)).unwrap();
    let seed = 7;
    let model = material(DamageModel::GradyKipp { model: gk, seed });
    let m = model.longitudinal_modulus();
    let mut sim = Simulation::new(with_material(positions.clone(), dx, model, 1e9)).unwrap();
    // Independent copy of the flaws (same public seeding) and of the law's constants.
    let flaws = gk.seed_flaws(n, volume, seed);
    let first = gk.activation_strain(1, volume);
    assert!((first - 1e-3).abs() < 1e-15);
    let crack_speed = 0.4 * (m / 1.0f64).sqrt(); // c_g = 0.4 c_l, ρ = 1
    let radius = 0.5 * dx; // R_s = ½Δx
    let stretch_for = |eps_eff: f64| strain_for(eps_eff).exp();
    sim.step().unwrap();
    // Ramp to 0.98 ε_1: no flaw is active, so nothing may damage.
    let below = stretch_for(0.98 * first);
    let mut f = 1.0;
    for k in 1..=200 {
        let next = 1.0 + (below - 1.0) * k as f64 / 200.0;
        drive_to(&mut sim, &positions, f, next);
        f = next;
        assert!((0..n).all(|i| sim.sample(ParticleField::Damage, i) == 0.0));
    }
    // Ramp to ε_eff = 1.85e-3 (a part of the flaws active), then hold.
    let above = stretch_for(1.85e-3);
    let mut previous: Vec<f64> = vec![0.0; n];
    let (mut grown, mut capped) = (0, 0);
    for k in 1..=40 {
        let next = if k <= 20 {
            f + (above - f) / (21 - k) as f64
        } else {
            above
        };
        let dt = sim.next_dt();
        drive_to(&mut sim, &positions, f, next);
        f = next;
        let eps_eff = effective(f.ln());
        for i in 0..n {
            let d = sim.sample(ParticleField::Damage, i);
            let active = flaws[i].iter().filter(|&&t| t <= eps_eff).count();
            let cap = if flaws[i].is_empty() {
                0.0
            } else {
                active as f64 / flaws[i].len() as f64
            };
            let d_old = previous[i];
            if d_old >= 1.0 || active == 0 {
                assert_eq!(d, d_old, "particle {i}: damage without active flaws");
            } else if d < cap {
                // Uncapped growth: Δ(D^{1/3}) = Δt n_act c_g / R_s exactly.
                let growth = d.cbrt() - d_old.cbrt();
                let law = dt * active as f64 * crack_speed / radius;
                assert!(
                    (growth - law).abs() < 1e-12 * law,
                    "particle {i}: ΔD^(1/3) = {growth}, law {law}"
                );
                grown += 1;
            } else {
                assert!(
                    d == cap.max(d_old) || (cap >= 1.0 && d == 1.0),
                    "particle {i}: D = {d}, cap {cap}"
                );
                capped += 1;
            }
            previous[i] = d;
        }
    }
    assert!(grown > 10 && capped > 10, "grown {grown}, capped {capped}");
    // A particle whose flaws are all active reaches D = 1 and fails (numerics.md §9.3).
    let eps_eff = effective(f.ln());
    let all_active = (0..n)
        .filter(|&i| !flaws[i].is_empty() && flaws[i].iter().all(|&t| t <= eps_eff))
        .count();
    assert!(all_active > 0);
    assert_eq!(sim.failed_particles(), all_active);
}

#[test]
fn grady_kipp_patch_has_no_damage_below_the_first_flaw_and_grows_by_the_law() {
    // Elastic, plane strain, F = diag(f, 1): σ1 = σ_xx = M ln f, so ε_eff = M ε / E.
    let elastic = LinearElastic::new(1.0, 0.3).unwrap();
    let (e, m) = (elastic.youngs_modulus(), elastic.longitudinal_modulus());
    grady_kipp_patch_follows_the_law(
        |damage| MaterialModel::ElasticDamage(ElasticDamage { elastic, damage }),
        |strain| m * strain / e,
        |eps_eff| eps_eff * e / m,
    );
}

#[test]
fn grady_kipp_on_a_yielding_plastic_patch_reads_its_effective_stress() {
    // Von Mises, perfectly plastic, σ_y = 2e-4 (E = 1, ν = 0.3): the patch yields at
    // ε_y = σ_y/2G = 2.6e-4, far below the first flaw. Past yield σ1 = σ_xx = K ε + ⅔σ_y
    // (pressure K ε, deviator held at ⅔σ_y), so ε_eff = (K ε + ⅔σ_y)/E. Damage read from the
    // elastic stress M ε would start at ε = 7.4e-4; the law's 1.04e-3 is where this one must.
    let elastic = LinearElastic::new(1.0, 0.3).unwrap();
    let sigma_y = 2e-4;
    let (e, k) = (elastic.youngs_modulus(), elastic.bulk_modulus());
    let yield_strain = sigma_y / (2.0 * elastic.shear_modulus());
    assert!(yield_strain < 0.5 * 0.98e-3 * e / elastic.longitudinal_modulus());
    grady_kipp_patch_follows_the_law(
        |damage| plastic_with_damage(elastic, sigma_y, damage),
        |strain| (k * strain + 2.0 / 3.0 * sigma_y) / e,
        |eps_eff| (e * eps_eff - 2.0 / 3.0 * sigma_y) / k,
    );
}

/// A hypoelastic, perfectly plastic von Mises material of yield stress `sigma_y` that softens
/// by `damage`.
fn plastic_with_damage(elastic: LinearElastic, sigma_y: f64, damage: DamageModel) -> MaterialModel {
    MaterialModel::ElasticPlastic(ElasticPlastic {
        elastic,
        strength: StrengthModel::VonMises(VonMisesPlasticity::new(sigma_y, 0.0).unwrap()),
        pressure: PressureModel::Hypoelastic,
        min_pressure: None,
        thermal: None,
        failure: None,
        damage: Some(damage),
    })
}

#[test]
fn peerlings_softens_a_yielding_plastic_patch_through_its_effective_stress() {
    // 1D (uniaxial strain), E = 1, ν = 0 (K = ⅓, G = ½, M = 1), σ_y = 5e-4: yield at
    // ε_y = σ_y/2G = 5e-4, before damage starts at κ0 = 1e-3. The effective stress is the
    // plastic one: σ_xx = M ε up to ε_y, then K ε + ⅔σ_y, and σ_yy = σ_zz = K ε − ⅓σ_y
    // (≥ 0 past yield). The body feels each positive principal value times (1 − D(ε))
    // (numerics.md §9.1), and the plastic strain runs on undisturbed by the damage. Same 1e-12
    // argument as the elastic patch above. The patch fails at κc.
    assert!(!peerlings_plastic_patch(None, 0.0));
}

#[test]
fn a_failure_criterion_fails_a_softening_plastic_patch_when_it_comes_first() {
    // The patch above with a maximum-plastic-strain criterion as well: ε̄p = ⅔(ε − ε_y)
    // reaches the limit 4e-3 at ε = 6.5e-3, inside the softening branch (D = 0.61). Up to
    // there the patch follows the softened law, and from there on every particle has failed.
    assert!(peerlings_plastic_patch(Some(4e-3), 0.0));
}

#[test]
fn a_particle_reaching_both_limits_in_one_step_fails_once() {
    // The limit put between ε̄p of the last step below κc and of the first at or above it:
    // both mechanisms fail the patch in that step, and each particle must be counted once (the
    // softening law is not advanced in a step the criterion fails the particle; advancing it
    // as well counted 24 failures of the 12 particles).
    let strains = driven_strains();
    let first = strains.iter().position(|&e| e >= KAPPA_C).unwrap();
    let between = 0.5 * (strains[first - 1] + strains[first]);
    let limit = 2.0 / 3.0 * (between - 5e-4);
    // Fails at κc, not before: the criterion's own step.
    assert!(!peerlings_plastic_patch(Some(limit), 0.0));
}

#[test]
fn an_initial_damage_on_a_yielding_plastic_patch_holds_until_its_history_then_softens() {
    // The patch of the first test above started at D0 = D(0.005), as if loaded to ε = 0.005
    // and unloaded: its effective stress is that of the virgin plastic patch (the damage does
    // not touch the plastic flow), felt with (1 − D0) up to ε = 0.005 and with the virgin D(ε)
    // beyond (numerics.md §9.1).
    assert!(!peerlings_plastic_patch(None, 0.005));
}

/// Drives the 1D Peerlings patch of a yielding plastic material (see the first caller), with
/// a maximum-plastic-strain failure criterion `failure_limit` when given and started at the
/// damage D(`damaged_to`) (0: intact), past failure, checking σ, ε̄p and the damage field
/// against the laws at every step. Returns whether the patch failed while its damage D was
/// still below 1 (by the criterion).
fn peerlings_plastic_patch(failure_limit: Option<f64>, damaged_to: f64) -> bool {
    use tlsph_materials::MaxPlasticStrainFailure;
    let dx = 1.0;
    let positions = lattice([12], dx);
    let elastic = LinearElastic::new(1.0, 0.0).unwrap();
    let sigma_y = 5e-4;
    let law = PeerlingsSoftening::new(KAPPA0, KAPPA_C).unwrap();
    let mut material = plastic_with_damage(elastic, sigma_y, DamageModel::Peerlings(law));
    if let (MaterialModel::ElasticPlastic(p), Some(limit)) = (&mut material, failure_limit) {
        p.failure = Some(tlsph_solver::FailureModel::MaxPlasticStrain(
            MaxPlasticStrainFailure::new(limit).unwrap(),
        ));
    }
    let mut m = with_material(positions.clone(), dx, material, 1e9);
    if damaged_to > 0.0 {
        m.bodies[0].initial_damage = Some(vec![law.damage(damaged_to); positions.len()]);
    }
    let mut sim = Simulation::new(m).unwrap();
    assert!(sim.has_failure());
    sim.step().unwrap();
    let (bulk, yield_strain) = (1.0 / 3.0, 5e-4);
    let mut failed_by_criterion = false;
    let mut held = 0;
    drive_past_failure(&mut sim, &positions, |sim, k, strain, failed_now| {
        // The history is κ(D0) = `damaged_to` to rounding: steps within 1e-12 of it are skipped.
        if damaged_to > 0.0 && (strain - damaged_to).abs() < 1e-12 {
            return;
        }
        if strain < damaged_to {
            held += 1;
        }
        let (xx, yy, plastic) = if strain <= yield_strain {
            (strain, 0.0, 0.0)
        } else {
            (
                bulk * strain + 2.0 / 3.0 * sigma_y,
                bulk * strain - sigma_y / 3.0,
                // Δε̄p = ⅔ Δε once the deviator is held on the surface.
                2.0 / 3.0 * (strain - yield_strain),
            )
        };
        // κ = max(ε, κ(D0)) on this monotone path.
        let d = law.damage(strain.max(damaged_to));
        if let Some(limit) = failure_limit {
            // Away from the limit by more than round-off, the criterion decides.
            if (plastic - limit).abs() > 1e-9 {
                assert_eq!(failed_now, plastic > limit, "step {k}: ε̄p = {plastic}");
            }
            failed_by_criterion |= failed_now && d < 1.0;
        }
        let felt = |s: f64| if s > 0.0 { (1.0 - d) * s } else { s };
        let (xx, yy) = if failed_now {
            (0.0, 0.0)
        } else {
            (felt(xx), felt(yy))
        };
        for i in 0..positions.len() {
            let sigma = sim.stresses()[i];
            assert!(
                (sigma[(0, 0)] - xx).abs() < 1e-12 && (sigma[(1, 1)] - yy).abs() < 1e-12,
                "step {k}, ε = {strain}: σ_xx = {}, σ_yy = {}, expected {xx}, {yy}",
                sigma[(0, 0)],
                sigma[(1, 1)]
            );
            if !failed_now {
                let ep = sim.sample(ParticleField::PlasticStrain, i);
                assert!(
                    (ep - plastic).abs() < 1e-12,
                    "step {k}: ε̄p = {ep}, {plastic}"
                );
                let damage = sim.sample(ParticleField::Damage, i);
                assert!((damage - d).abs() < 1e-12, "step {k}: D = {damage}, {d}");
            }
        }
    });
    if damaged_to > 0.0 {
        assert!(held > 1000, "{held} steps below the initial history");
    }
    failed_by_criterion
}

/// A 2D bar pulled apart at both ends until Grady–Kipp damage fails particles; elastic, or
/// with `yield_stress` elastic–plastic. Returns the damage field and stresses.
fn pulled_bar(
    seed: u64,
    threads: usize,
    yield_stress: Option<f64>,
) -> (Vec<f64>, Vec<tlsph_math::Tensor3>, usize) {
    super::on_threads(threads, || {
        let dx = 1.0;
        let positions = lattice([30, 8], dx);
        let n = positions.len();
        let volume = n as f64;
        let elastic = LinearElastic::new(1.0, 0.3).unwrap();
        let gk = GradyKipp::new(GK_M, gk_k(volume)).unwrap();
        let damage = DamageModel::GradyKipp { model: gk, seed };
        let material = match yield_stress {
            None => MaterialModel::ElasticDamage(ElasticDamage { elastic, damage }),
            Some(sigma_y) => plastic_with_damage(elastic, sigma_y, damage),
        };
        let mut m = with_material(positions.clone(), dx, material, 120.0);
        let ends = |left: bool| -> Vec<usize> {
            (0..n)
                .filter(|&i| (positions[i][0] < 1.0) == left && (positions[i][0] > 29.0) != left)
                .collect()
        };
        for (name, left, v) in [("left", true, -2e-3), ("right", false, 2e-3)] {
            m.boundaries.push(tlsph_solver::BoundaryDescription {
                name: name.into(),
                body: 0,
                particles: ends(left),
                velocity: Vector::<2>::new(v, 0.0),
                components: [true, false],
                amplitude: None,
            });
        }
        let mut sim = Simulation::new(m).unwrap();
        sim.run(|_, _| {}).unwrap();
        if yield_stress.is_some() {
            // The plastic variant really yields somewhere.
            let largest = (0..n)
                .map(|i| sim.sample(ParticleField::PlasticStrain, i))
                .fold(0.0, f64::max);
            assert!(largest > 1e-4, "largest plastic strain {largest}");
        }
        let damage = (0..n)
            .map(|i| sim.sample(ParticleField::Damage, i))
            .collect();
        (damage, sim.stresses().to_vec(), sim.failed_particles())
    })
}

#[test]
fn damaged_runs_are_deterministic_and_follow_the_seed() {
    // Elastic, and elastic–plastic with σ_y = 1e-3 (E = 1, the first flaw at a tensile
    // stress of 1e-3): that bar yields (asserted in `pulled_bar`) and damages.
    for yield_stress in [None, Some(1e-3)] {
        let (d1, s1, failed) = pulled_bar(11, 1, yield_stress);
        let (d2, s2, failed2) = pulled_bar(11, 2, yield_stress);
        // The run really damaged and failed particles ...
        assert!(
            failed > 0 && d1.iter().any(|&d| d > 0.0 && d < 1.0),
            "{yield_stress:?}: {failed} failed"
        );
        // ... bit-identically for one and two threads with the same seed ...
        assert_eq!(failed, failed2);
        assert!(d1.iter().zip(&d2).all(|(a, b)| a.to_bits() == b.to_bits()));
        assert!(s1.iter().zip(&s2).all(|(a, b)| a
            .iter()
            .zip(b.iter())
            .all(|(x, y)| x.to_bits() == y.to_bits())));
        // ... and another seed places the flaws elsewhere.
        let (d3, _, _) = pulled_bar(12, 2, yield_stress);
        assert!(d1.iter().zip(&d3).any(|(a, b)| a != b));
    }
}

#[test]
fn damage_needs_the_jaumann_rate_update() {
    let dx = 1.0;
    let law = PeerlingsSoftening::new(KAPPA0, KAPPA_C).unwrap();
    let mut m = damaged(
        lattice([6], dx),
        dx,
        LinearElastic::new(1.0, 0.0).unwrap(),
        DamageModel::Peerlings(law),
        1.0,
    );
    m.config.stress_update = StressUpdate::GreenLagrange;
    match Simulation::new(m) {
        Err(SetupError::InvalidConfig { field, .. }) => assert_eq!(field, "stress_update"),
        other => panic!("expected a stress_update error, got {other:?}"),
    }
}

#[test]
fn initial_peerlings_damage_reloads_on_the_secant_then_softens_like_the_virgin_law() {
    // A patch started at D0 = D(0.005) is the patch of the test above that was loaded to
    // ε = 0.005 and unloaded: pulled again it carries σ = (1 − D0)Eε up to ε = 0.005 (the
    // history κ(D0) = 0.005), then the virgin softening line, to failure (numerics.md §9.1).
    let dx = 1.0;
    let positions = lattice([10], dx);
    let law = PeerlingsSoftening::new(KAPPA0, KAPPA_C).unwrap();
    let mut m = damaged(
        positions.clone(),
        dx,
        LinearElastic::new(1.0, 0.0).unwrap(),
        DamageModel::Peerlings(law),
        1e9,
    );
    let d0 = law.damage(0.005);
    m.bodies[0].initial_damage = Some(vec![d0; positions.len()]);
    let mut sim = Simulation::new(m).unwrap();
    assert_eq!(sim.sample(ParticleField::Damage, 5), d0);
    sim.step().unwrap();
    let (mut secant, mut beyond) = (0, 0);
    drive_past_failure(&mut sim, &positions, |sim, k, strain, _| {
        // The history is κ(D0) = 0.005 to rounding: steps within 1e-12 of it are skipped.
        if (strain - 0.005).abs() < 1e-12 {
            return;
        }
        let expected = if strain < 0.005 {
            secant += 1;
            (1.0 - d0) * strain
        } else {
            beyond += 1;
            peerlings_uniaxial(1.0, strain)
        };
        for i in 0..positions.len() {
            let sigma = sim.stresses()[i][(0, 0)];
            assert!(
                (sigma - expected).abs() < 1e-12,
                "step {k}, ε = {strain}: σ = {sigma}, expected {expected}"
            );
        }
    });
    assert!(
        secant > 1000 && beyond > 1000,
        "{secant} secant, {beyond} beyond"
    );
}

#[test]
fn initial_grady_kipp_damage_softens_until_the_flaws_grow_it() {
    // An elastic patch started at D0 = 0.3, pulled below its first flaw: the damage stays D0
    // and the patch carries σ_xx = (1 − D0)M ε (plane strain, every principal stress tensile);
    // an undamaged twin carries M ε.
    let dx = 1.0;
    let positions = lattice([6, 6], dx);
    let n = positions.len();
    let elastic = LinearElastic::new(1.0, 0.3).unwrap();
    let volume = n as f64 * dx * dx;
    let gk = GradyKipp::new(GK_M, gk_k(volume)).unwrap();
    let model = DamageModel::GradyKipp { model: gk, seed: 3 };
    let d0 = 0.3;
    let run = |initial: Option<Vec<f64>>| {
        let mut m = damaged(positions.clone(), dx, elastic, model, 1e9);
        m.bodies[0].initial_damage = initial;
        let mut sim = Simulation::new(m).unwrap();
        sim.step().unwrap();
        // ε_eff = σ_xx/E = M ε/E: 0.9 of the first flaw's strain.
        let e_over_m = elastic.youngs_modulus() / elastic.longitudinal_modulus();
        let below = (0.9 * gk.activation_strain(1, volume) * e_over_m).exp();
        let mut f = 1.0;
        for k in 1..=100 {
            let next = 1.0 + (below - 1.0) * k as f64 / 100.0;
            drive_to(&mut sim, &positions, f, next);
            f = next;
        }
        let damage: Vec<f64> = (0..n)
            .map(|i| sim.sample(ParticleField::Damage, i))
            .collect();
        (damage, sim.stresses()[n / 2][(0, 0)], f.ln())
    };
    let (damage, sigma, strain) = run(Some(vec![d0; n]));
    let (virgin_damage, virgin_sigma, _) = run(None);
    assert!(damage.iter().all(|&d| d == d0), "{damage:?}");
    assert!(virgin_damage.iter().all(|&d| d == 0.0));
    let m = elastic.longitudinal_modulus();
    assert!((virgin_sigma - m * strain).abs() < 1e-9 * virgin_sigma);
    assert!((sigma - (1.0 - d0) * virgin_sigma).abs() < 1e-12 * virgin_sigma);
}

#[test]
fn initial_damage_is_refused_outside_0_to_1_and_without_a_damage_law() {
    let dx = 1.0;
    let positions = lattice([6], dx);
    let law = PeerlingsSoftening::new(KAPPA0, KAPPA_C).unwrap();
    let elastic = LinearElastic::new(1.0, 0.0).unwrap();
    let with = |damage: Vec<f64>, material_has_law: bool| {
        let mut m = damaged(
            positions.clone(),
            dx,
            elastic,
            DamageModel::Peerlings(law),
            1.0,
        );
        if !material_has_law {
            m.materials[0].model = MaterialModel::LinearElastic(elastic);
        }
        m.bodies[0].initial_damage = Some(damage);
        refused_as(m, "initial_damage")
    };
    assert_damage_values_checked(|damage| with(damage, true));
    assert!(with(vec![0.5; 6], false).contains("has no damage law"));
}

/// The message of the setup error of `m`, which must be refused as an invalid `field`.
fn refused_as(m: Model<1>, field: &str) -> String {
    match Simulation::new(m) {
        Err(SetupError::InvalidConfig {
            field: got,
            message,
        }) if got == field => message,
        other => panic!("expected a {field} error, got {other:?}"),
    }
}

/// Asserts that an initial damage setter on a body of 6 particles (`refusal(values)` returns
/// its error message) refuses D = 1, −0.1 and NaN at particle 4, naming it and the rule, and a
/// wrong number of values.
fn assert_damage_values_checked(refusal: impl Fn(Vec<f64>) -> String) {
    for bad in [1.0, -0.1, f64::NAN] {
        let mut damage = vec![0.5; 6];
        damage[4] = bad;
        let message = refusal(damage);
        assert!(message.contains("particle 4 at [4.5e0]"), "{message}");
        assert!(message.contains("0 ≤ D < 1"), "{message}");
    }
    let message = refusal(vec![0.5; 5]);
    assert!(
        message.contains("has 6 particles but 5 damage values"),
        "{message}"
    );
}

/// A 1D perfectly plastic von Mises material (E = 1, ν = 0, yield stress `sigma_y`) with a
/// Johnson–Cook failure law of constant failure strain `strain_to_failure` = D1 (D2 … D5 = 0),
/// with adiabatic heating when `heated`.
fn johnson_cook_failing(sigma_y: f64, strain_to_failure: f64, heated: bool) -> MaterialModel {
    MaterialModel::ElasticPlastic(ElasticPlastic {
        elastic: LinearElastic::new(1.0, 0.0).unwrap(),
        strength: StrengthModel::VonMises(VonMisesPlasticity::new(sigma_y, 0.0).unwrap()),
        pressure: PressureModel::Hypoelastic,
        min_pressure: None,
        thermal: heated.then_some(tlsph_solver::Thermal {
            specific_heat: 1.0,
            room_temperature: 293.0,
        }),
        failure: Some(tlsph_solver::FailureModel::JohnsonCook {
            model: tlsph_materials::JohnsonCookFailure::new(strain_to_failure, 0.0, 0.0, 0.0, 0.0)
                .unwrap(),
            reference_strain_rate: 1.0,
            room_temperature: 293.0,
            melt_temperature: 1356.0,
        }),
        damage: None,
    })
}

/// A 1D perfectly plastic von Mises patch (E = 1, ν = 0, σ_y = 5e-4) with a Johnson–Cook
/// failure law of constant failure strain ε_f = D1 = 2e-3 (D2 … D5 = 0), started at the
/// failure damage `initial` (if given), driven through [`driven_stretches`]; returns the
/// Hencky strain at which every particle has failed. `heated`: with adiabatic heating (the
/// state then also carries a temperature; ε_f does not depend on it, D5 = 0).
fn johnson_cook_patch_failure_strain(initial: Option<f64>, heated: bool) -> f64 {
    let dx = 1.0;
    let positions = lattice([8], dx);
    let n = positions.len();
    let (sigma_y, strain_to_failure) = (5e-4, 2e-3);
    let material = johnson_cook_failing(sigma_y, strain_to_failure, heated);
    let mut m = with_material(positions.clone(), dx, material, 1e9);
    m.bodies[0].initial_failure_damage = initial.map(|d| vec![d; n]);
    let mut sim = Simulation::new(m).unwrap();
    let d0 = initial.unwrap_or(0.0);
    assert_eq!(sim.sample(ParticleField::Damage, 3), d0);
    sim.step().unwrap();
    let mut f = 1.0;
    for (k, next) in (1..).zip(driven_stretches()) {
        drive_to(&mut sim, &positions, f, next);
        f = next;
        let strain = f.ln();
        if sim.failed_particles() == n {
            return strain;
        }
        assert_eq!(
            sim.failed_particles(),
            0,
            "step {k}: the patch fails as one"
        );
        // D = D0 + ε̄p/ε_f with ε̄p = ⅔(ε − ε_y) past yield (Δε̄p = ⅔Δε on the surface). ε̄p
        // follows this to 1e-12 (the plastic patch above), so D to 1e-12/ε_f = 5e-10.
        let plastic = (2.0 / 3.0 * (strain - sigma_y)).max(0.0);
        let expected = d0 + plastic / strain_to_failure;
        for i in 0..n {
            let d = sim.sample(ParticleField::Damage, i);
            assert!((d - expected).abs() < 1e-9, "step {k}: D = {d}, {expected}");
        }
    }
    panic!("the patch did not fail by ε = 0.012");
}

#[test]
fn an_initial_johnson_cook_damage_leaves_the_rest_of_the_failure_strain() {
    // Started at D0 the patch fails once ε̄p/ε_f adds 1 − D0 (numerics.md §8.6): at
    // ε̄p = (1 − D0) ε_f, ε = ε_y + 1.5 (1 − D0) ε_f; intact at ε = 3.5e-3, with D0 = 0.5 at
    // 2e-3 and with D0 = 0.9 at 8e-4. The patch is driven in steps of Δε = 4e-6, so it fails
    // in the step that crosses the strain: within 4e-6 above it.
    let (yield_strain, strain_to_failure) = (5e-4, 2e-3);
    // With heating the damage sits at another place of the particle's state.
    for (d0, heated) in [
        (None, false),
        (Some(0.5), false),
        (Some(0.9), false),
        (Some(0.5), true),
    ] {
        let failed_at = johnson_cook_patch_failure_strain(d0, heated);
        let expected = yield_strain + 1.5 * (1.0 - d0.unwrap_or(0.0)) * strain_to_failure;
        assert!(
            failed_at >= expected - 1e-12 && failed_at < expected + 4.1e-6,
            "D0 = {d0:?}, heated {heated}: failed at ε = {failed_at}, expected {expected}"
        );
    }
}

#[test]
fn an_initial_johnson_cook_damage_is_refused_outside_0_to_1_and_without_the_law() {
    let dx = 1.0;
    let positions = lattice([6], dx);
    let elastic = LinearElastic::new(1.0, 0.0).unwrap();
    let law = PeerlingsSoftening::new(KAPPA0, KAPPA_C).unwrap();
    let with = |damage: Vec<f64>, material: MaterialModel| {
        let mut m = with_material(positions.clone(), dx, material, 1.0);
        m.bodies[0].initial_failure_damage = Some(damage);
        refused_as(m, "initial_failure_damage")
    };
    let johnson_cook = johnson_cook_failing(1.0, 0.5, false);
    assert_damage_values_checked(|damage| with(damage, johnson_cook));
    // A softening law is not a Johnson–Cook failure law.
    let softening = plastic_with_damage(elastic, 1.0, DamageModel::Peerlings(law));
    assert!(with(vec![0.5; 6], softening).contains("has no Johnson–Cook failure law"));
    // And the softening key names this one on a material with only the failure law.
    let mut m = with_material(positions.clone(), dx, johnson_cook, 1.0);
    m.bodies[0].initial_damage = Some(vec![0.5; 6]);
    let message = refused_as(m, "initial_damage");
    assert!(
        message.contains("set by `initial_failure_damage`"),
        "{message}"
    );
}
