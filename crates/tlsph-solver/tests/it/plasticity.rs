//! Elastic–plastic bodies: the solver's constitutive wiring reproduces a material-point
//! integration of the same model on a homogeneous deformation path.

use super::{lattice, model, Setup};
use tlsph_materials::{LinearElastic, VonMisesPlasticity};
use tlsph_math::{deviator, Tensor, Tensor3, Vector};
use tlsph_solver::{
    ElasticPlastic, Formulation, MaterialModel, ParticleField, PressureModel, Simulation,
    StrengthModel, StressUpdate,
};

/// The M-CU6 copper of R-P6 (numerics.md §8.2 linear hardening, E_t = 1.1 GPa).
pub(super) fn copper() -> ElasticPlastic {
    let elastic = LinearElastic::new(110e9, 0.343).unwrap();
    ElasticPlastic {
        elastic,
        strength: StrengthModel::VonMises(
            VonMisesPlasticity::from_tangent_modulus(90e6, 110e9, 1.1e9).unwrap(),
        ),
        pressure: PressureModel::Hypoelastic,
        min_pressure: None,
        thermal: None,
        failure: None,
        damage: None,
    }
}

#[test]
fn homogeneous_compression_matches_the_material_point() {
    // A 2D block driven through F(t) = diag(1 − ε̇t, 1) (plane-strain uniaxial compression to
    // 5 %). With corrected gradients every particle sees the exact F, so each must follow the
    // material-point integration of the same model with the same steps to round-off.
    let dx = 1e-3;
    let positions = lattice([8, 6], dx);
    let mut m = model(
        positions.clone(),
        dx,
        |_| Vector::<2>::zeros(),
        Setup {
            formulation: Formulation::TotalLagrangianCorrected,
            stress_update: StressUpdate::JaumannRate,
            end_time: 1.0,
            ..Setup::default()
        },
    );
    let material = copper();
    m.materials[0].density = 8990.0;
    m.materials[0].model = MaterialModel::ElasticPlastic(material);
    let mut sim = Simulation::new(m).unwrap();
    let rate = 1000.0; // compressive strain rate [1/s]
    let steps = 100;
    let dt_drive = 0.05 / rate / steps as f64;
    let stretch = |t: f64| 1.0 - rate * t;
    let displacement = |t: f64| -> Vec<Vector<2>> {
        positions
            .iter()
            .map(|x| Vector::<2>::new((stretch(t) - 1.0) * x[0], 0.0))
            .collect()
    };
    sim.step().unwrap();
    // Material point: same midpoint kinematics as the solver, D_xx = −ε̇/λ^{n−½}.
    let (g, k) = (
        material.elastic.shear_modulus(),
        material.elastic.bulk_modulus(),
    );
    let StrengthModel::VonMises(vm) = material.strength else {
        unreachable!()
    };
    let mut s = Tensor3::zeros();
    let mut p = 0.0;
    let mut ep = 0.0;
    let mut t = 0.0;
    for _ in 0..steps {
        let own = sim.next_dt();
        let now = displacement(t);
        let next = displacement(t + dt_drive);
        let v: Vec<Vector<2>> = now.iter().zip(&next).map(|(a, b)| (b - a) / own).collect();
        sim.set_displacements(&now);
        sim.set_velocities(&v);
        sim.step().unwrap();
        // The solver used Δt = own for this step with the same velocities.
        let f_dot = -rate * dt_drive / own;
        let f_half = stretch(t + dt_drive) - 0.5 * own * f_dot;
        let mut d = Tensor3::zeros();
        d[(0, 0)] = f_dot / f_half;
        p -= k * d.trace() * own;
        let trial = s + deviator(&d) * (2.0 * g * own);
        let ret = vm.return_map(&trial, g, ep);
        s = ret.deviator;
        ep += ret.plastic_strain_increment;
        t += dt_drive;
    }
    let expected = s - Tensor3::identity() * p;
    assert!(
        ep > 0.01,
        "the path must go well into the plastic range (ε̄p = {ep})"
    );
    for i in 0..sim.n_particles() {
        let sigma = sim.stresses()[i];
        assert!(
            (sigma - expected).norm() < 1e-6 * expected.norm(),
            "particle {i}: {sigma} vs {expected}"
        );
        let ep_i = sim.sample(ParticleField::PlasticStrain, i);
        assert!(
            (ep_i - ep).abs() < 1e-9 * ep,
            "particle {i}: ε̄p {ep_i} vs {ep}"
        );
    }
    let _ = Tensor::<2>::identity();
}

#[test]
fn plasticity_needs_the_rate_form() {
    let dx = 1e-3;
    let mut m = model(
        lattice([4, 4], dx),
        dx,
        |_| Vector::<2>::zeros(),
        Setup {
            stress_update: StressUpdate::GreenLagrange,
            ..Setup::default()
        },
    );
    m.materials[0].model = MaterialModel::ElasticPlastic(copper());
    let err = Simulation::new(m).unwrap_err();
    assert!(err.to_string().contains("jaumann-rate"), "{err}");
}

#[test]
fn a_failed_particle_leaves_every_sum_and_the_halves_separate() {
    // Both formulations: TLSPH rebuilds the survivors' reference gradients, conventional SPH
    // drops the failed particle from its current pairs.
    for formulation in [
        Formulation::TotalLagrangianCorrected,
        Formulation::UpdatedLagrangian,
    ] {
        failed_particle_case(formulation);
    }
}

/// The unit material (E 0.9, ν 0.2: c = 1) yielding at σ_y = 0.01 without hardening and failing
/// at ε̄p = 0.05: tears within a few percent of strain.
pub(super) fn brittle_plastic() -> MaterialModel {
    use tlsph_materials::MaxPlasticStrainFailure;
    use tlsph_solver::FailureModel;
    MaterialModel::ElasticPlastic(ElasticPlastic {
        elastic: LinearElastic::new(0.9, 0.2).unwrap(),
        strength: StrengthModel::VonMises(VonMisesPlasticity::new(0.01, 0.0).unwrap()),
        pressure: PressureModel::Hypoelastic,
        min_pressure: None,
        thermal: None,
        failure: Some(FailureModel::MaxPlasticStrain(
            MaxPlasticStrainFailure::new(0.05).unwrap(),
        )),
        damage: None,
    })
}

fn failed_particle_case(formulation: Formulation) {
    // A 1D bar whose halves fly apart at ±0.05 c: the centre yields in tension, reaches the
    // failure strain and fails; afterwards no tension crosses the gap, so the halves keep
    // moving apart, momentum stays zero, and the failed particle carries no stress.
    let dx = 0.01;
    let positions = lattice([100], dx);
    let mut m = model(
        positions.clone(),
        dx,
        |x| Vector::<1>::new(if x[0] < 0.5 { -0.05 } else { 0.05 }),
        Setup {
            formulation,
            end_time: 3.0,
            ..Setup::default()
        },
    );
    m.materials[0].model = brittle_plastic();
    let mut sim = Simulation::new(m).unwrap();
    let mut worst_p: f64 = 0.0;
    sim.run(|s, _| worst_p = worst_p.max(s.diagnostics().linear_momentum.x.abs()))
        .unwrap();
    assert!(sim.failed_particles() >= 1, "the centre must fail");
    assert!(worst_p < 1e-15, "momentum {worst_p:e}");
    let failed: Vec<usize> = (0..sim.n_particles())
        .filter(|&i| sim.sample(ParticleField::Damage, i) >= 1.0)
        .collect();
    assert_eq!(failed.len(), sim.failed_particles());
    for &i in &failed {
        assert_eq!(sim.stresses()[i], Tensor3::zeros());
        assert!(sim.is_failed(i));
        // No neighbours measure its volume: J and density are undefined, not J = 1 and ρ0.
        assert!(sim.sample(ParticleField::Jacobian, i).is_nan());
        assert!(sim.sample(ParticleField::Density, i).is_nan());
        // Failed particles sit near the centre, where the tension was largest.
        assert!(
            (positions[i][0] - 0.5).abs() < 0.1,
            "failed at {}",
            positions[i][0]
        );
    }
    // The halves separate: the right half moves right, the left half left.
    let v_left = sim.velocity(10)[0];
    let v_right = sim.velocity(89)[0];
    assert!(v_left < 0.0 && v_right > 0.0, "{v_left} {v_right}");
    let gap = sim.displacements()[99][0] - sim.displacements()[0][0];
    assert!(gap > 0.1, "halves did not separate: {gap}");
    // The failed particles' internal energy moves from `internal` to its own booked column:
    // exactly Σ m e over the failed particles, and the total is unchanged by the move.
    let d = sim.diagnostics();
    let deleted: f64 = failed
        .iter()
        .map(|&i| sim.masses()[i] * sim.internal_energies()[i])
        .sum();
    let all: f64 = (0..sim.n_particles())
        .map(|i| sim.masses()[i] * sim.internal_energies()[i])
        .sum();
    let column = d
        .effect_energies
        .iter()
        .find(|(name, _)| name == "deleted_particles")
        .map(|(_, e)| *e)
        .expect("a deleted_particles column with a failure model");
    assert!(deleted > 0.0);
    assert!((column - deleted).abs() <= 1e-12 * all.abs());
    assert!((d.internal + column - all).abs() <= 1e-12 * all.abs());
}

#[test]
fn the_time_step_follows_the_stiffening_of_an_equation_of_state() {
    // A copper rod (Mie–Grüneisen, M-CU9) compressed uniformly to J = 0.75 (μ = 1/3) before
    // the first step. Its sound speed is sqrt((K_s + 4G/3)/ρ) with K_s the EOS's isentropic
    // modulus there, 2.46 ρ0C²; the constant-modulus estimate c0 sqrt(J) would give a step
    // 1.6 times too long (numerics.md §8.10), past the stability limit at CFL 0.7 and more.
    use tlsph_materials::eos::MieGruneisenParameters;
    use tlsph_materials::{EquationOfState, MieGruneisen};
    let (n, dx, rho0) = (40, 1e-4, 8924.0);
    let eos: EquationOfState = MieGruneisen::new(MieGruneisenParameters {
        reference_density: rho0,
        sound_speed: 3940.0,
        s1: 1.489,
        s2: 0.0,
        s3: 0.0,
        gamma0: 2.02,
        a: 0.47,
    })
    .unwrap()
    .into();
    let mut material = copper();
    material.pressure = PressureModel::Eos(eos);
    let shear = material.elastic.shear_modulus();
    // The rod at rest, uniformly compressed to J before its first step.
    let compressed_rod = |j: f64| {
        let mut m = model(
            lattice([n], dx),
            dx,
            |_| Vector::<1>::zeros(),
            Setup::default(),
        );
        m.materials[0].density = rho0;
        m.materials[0].model = MaterialModel::ElasticPlastic(material);
        let mut sim = Simulation::new(m).unwrap();
        let u: Vec<Vector<1>> = lattice([n], dx).iter().map(|x| x * (j - 1.0)).collect();
        sim.set_displacements(&u);
        sim
    };
    let j = 0.75;
    let mut sim = compressed_rod(j);
    // The first step has Δt = 0: no energy is deposited, so E_v = 0 at the new step's vote.
    sim.step().unwrap();
    for i in 0..n {
        let jacobian = sim.sample(ParticleField::Jacobian, i);
        assert!((jacobian - j).abs() < 1e-12, "corrected gradients: J exact");
    }
    let mu = 1.0 / j - 1.0;
    let k_s = eos.isentropic_bulk_modulus(mu, 0.0);
    let c = ((k_s + 4.0 / 3.0 * shear) * j / rho0).sqrt();
    let h = 1.2 * dx;
    let expected = 0.3 * h / c;
    assert!(
        (sim.next_dt() / expected - 1.0).abs() < 1e-12,
        "Δt = {:e}, expected {expected:e}",
        sim.next_dt()
    );
    let constant_modulus = 0.3 * h
        / (((eos.bulk_modulus_at_reference() + 4.0 / 3.0 * shear) / rho0).sqrt() * j.sqrt());
    assert!(
        constant_modulus / expected > 1.55,
        "the stiffening matters here: {constant_modulus:e} vs {expected:e}"
    );
    // Beyond the limiting compression μ_lim = 1/(S1 − 1) = 2.04 (J < 0.329) the sound speed
    // is infinite: the step collapses with an error that names the particle and says why.
    match compressed_rod(0.3).step().unwrap_err() {
        tlsph_solver::StepError::TimeStepCollapse {
            particle: Some(limiting),
            ..
        } => assert_eq!(limiting.sound_speed, f64::INFINITY),
        other => panic!("unexpected {other}"),
    }
}

/// A 4 × 4 block (spacing 1 mm, ρ = 8930 kg/m³) of `material`, at rest.
fn copper_block(material: ElasticPlastic) -> Simulation<2> {
    Simulation::new(copper_block_model(material)).unwrap()
}

/// The model of [`copper_block`].
fn copper_block_model(material: ElasticPlastic) -> tlsph_solver::Model<2> {
    let dx = 1e-3;
    let mut m = model(
        lattice([4, 4], dx),
        dx,
        |_| Vector::<2>::zeros(),
        Setup::default(),
    );
    m.materials[0].density = 8930.0;
    m.materials[0].model = MaterialModel::ElasticPlastic(material);
    m
}

#[test]
fn a_material_with_heating_and_failure_reports_its_temperature() {
    // Before, `has_temperature` missed the [ε̄p, T, D, status] state, so frames of a material
    // with both `specific_heat` and `failure` dropped the temperature array.
    use tlsph_materials::MaxPlasticStrainFailure;
    use tlsph_solver::{FailureModel, Thermal};
    let room = 293.0;
    let mut material = copper();
    material.thermal = Some(Thermal {
        specific_heat: 383.0,
        room_temperature: room,
    });
    material.failure = Some(FailureModel::MaxPlasticStrain(
        MaxPlasticStrainFailure::new(0.5).unwrap(),
    ));
    let mut sim = copper_block(material);
    sim.step().unwrap();
    assert!(sim.has_temperature() && sim.has_failure());
    assert_eq!(sim.sample(ParticleField::Temperature, 5), room);
}

#[test]
fn a_starting_stress_outside_the_yield_surface_is_refused() {
    // σ_y0 = 90 MPa: a uniaxial 100 MPa would be returned to the surface by the first step.
    let build = || copper_block(copper());
    let uniaxial = |s: f64| Tensor3::new(s, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let error = build().set_initial_stress(0, uniaxial(100e6)).unwrap_err();
    assert!(error.to_string().contains("yield surface"), "{error}");
    assert!(build().set_initial_stress(0, uniaxial(90e6)).is_ok());
    assert!(build()
        .set_initial_stress(0, Tensor3::identity() * -1e9)
        .is_ok());
    // A field that rises along x past 90 MPa: refused at the first particle beyond it, named.
    let x_max = build()
        .positions0()
        .iter()
        .map(|x| x.x)
        .fold(f64::MIN, f64::max);
    let rising = |x: &tlsph_math::Vector<2>| uniaxial(95e6 * x.x / x_max);
    let error = build().set_initial_stress_field(0, rising).unwrap_err();
    let text = error.to_string();
    assert!(
        text.contains("yield surface") && text.contains("particle") && text.contains(" at ["),
        "{text}"
    );
    let within = |x: &tlsph_math::Vector<2>| uniaxial(85e6 * x.x / x_max);
    let mut sim = build();
    sim.set_initial_stress_field(0, within).unwrap();
    let last = sim.n_particles() - 1;
    let expected = 85e6 * sim.positions0()[last].x / x_max;
    assert_eq!(sim.stresses()[last][(0, 0)], expected);
}

#[test]
fn a_stress_per_particle_is_set_checked_and_exclusive() {
    let uniaxial = |s: f64| Tensor3::new(s, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let mut sim = copper_block(copper());
    let n = sim.n_particles();
    // One stress per particle, each particle its own.
    let stresses: Vec<Tensor3> = (0..n).map(|k| uniaxial(1e6 * k as f64)).collect();
    sim.set_initial_stresses(0, &stresses).unwrap();
    assert!(sim.stresses() == stresses.as_slice());
    // One too few: refused, naming the counts.
    let error = copper_block(copper())
        .set_initial_stresses(0, &stresses[1..])
        .unwrap_err()
        .to_string();
    assert!(
        error.contains(&format!("{n} particles but {} stresses", n - 1)),
        "{error}"
    );
    // Past the surface at one particle: refused, naming that particle.
    let mut outside = stresses.clone();
    outside[5] = uniaxial(100e6);
    let error = copper_block(copper())
        .set_initial_stresses(0, &outside)
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("particle 5 at [") && error.contains("yield surface"),
        "{error}"
    );
    // Through the model: the per-particle field is applied, and excludes a uniform one.
    let mut m = copper_block_model(copper());
    m.bodies[0].initial_stresses = Some(stresses.clone());
    let sim = Simulation::new(m.clone()).unwrap();
    assert!(sim.stresses() == stresses.as_slice());
    m.bodies[0].initial_stress = Some(uniaxial(1.0));
    let Err(error) = Simulation::new(m) else {
        panic!("a per-particle and a uniform stress together must be refused")
    };
    let error = error.to_string();
    assert!(
        error.contains("excludes a uniform or linear one"),
        "{error}"
    );
}

#[test]
fn the_quasi_static_yield_stress_is_the_flow_stress_at_the_reference_rate_and_room_temperature() {
    use tlsph_materials::strength::{JohnsonCookStrength, JohnsonCookStrengthParameters};
    use tlsph_solver::StrengthModel;
    // OFHC copper (Johnson and Cook 1983): A = 90 MPa, B = 292 MPa, n = 0.31.
    let parameters = JohnsonCookStrengthParameters::OFHC_COPPER;
    let model = JohnsonCookStrength::new(parameters).unwrap();
    let strength = StrengthModel::JohnsonCook {
        model,
        iterate: false,
    };
    for plastic_strain in [0.0, 0.05, 0.3, 1.0] {
        let expected = model.yield_stress(plastic_strain, 1.0, parameters.room_temperature);
        let got = strength.quasi_static_yield_stress(plastic_strain);
        assert!(
            (got / expected - 1.0).abs() < 1e-15,
            "{got:e} vs {expected:e}"
        );
    }
    assert_eq!(strength.quasi_static_yield_stress(0.0), 90e6);
}

#[test]
fn an_initial_plastic_strain_raises_the_yield_surface_and_is_checked() {
    use tlsph_materials::MaxPlasticStrainFailure;
    use tlsph_solver::FailureModel;
    // copper(): σ_y0 = 90 MPa; at ε̄p = 0.1 the yield stress is 90 MPa + 0.1 E_p.
    let uniaxial = |s: f64| Tensor3::new(s, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let material = copper();
    let hardened = material.strength.quasi_static_yield_stress(0.1);
    assert!(hardened > 90e6 * 1.001, "{hardened:e}");
    let mut m = copper_block_model(material);
    let n = m.bodies[0].positions.len();
    m.bodies[0].initial_plastic_strains = Some(vec![0.1; n]);
    m.bodies[0].initial_stress = Some(uniaxial(0.5 * (90e6 + hardened)));
    // Set before the stress, so the stress between the two yield stresses is admitted.
    let sim = Simulation::new(m.clone()).unwrap();
    assert_eq!(sim.sample(ParticleField::PlasticStrain, 3), 0.1);
    let mut virgin = m.clone();
    virgin.bodies[0].initial_plastic_strains = None;
    let Err(error) = Simulation::new(virgin) else {
        panic!("the stress lies outside the virgin yield surface")
    };
    assert!(error.to_string().contains("yield surface"), "{error}");
    // Refusals, each naming what is wrong.
    let refused = |strains: Vec<f64>, material: MaterialModel| {
        let mut m = copper_block_model(copper());
        m.materials[0].model = material;
        m.bodies[0].initial_plastic_strains = Some(strains);
        match Simulation::new(m) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("must be refused"),
        }
    };
    let ep = MaterialModel::ElasticPlastic(copper());
    let mut negative = vec![0.1; n];
    negative[7] = -0.01;
    let e = refused(negative, ep);
    assert!(e.contains("particle 7 at [") && e.contains("≥ 0"), "{e}");
    let e = refused(vec![0.1; n - 1], ep);
    assert!(e.contains(&format!("{n} particles but {}", n - 1)), "{e}");
    let elastic = MaterialModel::LinearElastic(LinearElastic::new(1e11, 0.3).unwrap());
    let e = refused(vec![0.1; n], elastic);
    assert!(e.contains("has no plastic strain"), "{e}");
    let mut failing = copper();
    failing.failure = Some(FailureModel::MaxPlasticStrain(
        MaxPlasticStrainFailure::new(0.1).unwrap(),
    ));
    let e = refused(vec![0.1; n], MaterialModel::ElasticPlastic(failing));
    assert!(
        e.contains("particle 0 at [") && e.contains("failure strain"),
        "{e}"
    );
}

#[test]
fn a_particle_whose_neighbours_all_fail_fails_with_them() {
    // A 1D bar prestressed in tension whose last two particles are launched outward at 0.2 c:
    // the bar tears at particles 97 and 98, and particle 99 (bonded to 97 and 98 only) is left
    // with no neighbour, a lone point mass that can carry no stress. Before the fix it kept
    // the stress it had at that instant (σ_xx = 0.013) for the rest of the run and in every
    // output, though nothing could change it any more.
    let dx = 0.01;
    let positions = lattice([100], dx);
    let mut m = model(
        positions,
        dx,
        |x| Vector::<1>::new(if x[0] > 0.975 { 0.2 } else { 0.0 }),
        Setup {
            end_time: 0.3,
            ..Setup::default()
        },
    );
    m.materials[0].model = brittle_plastic();
    let mut prestress = Tensor3::zeros();
    prestress[(0, 0)] = 0.005;
    m.bodies[0].initial_stress = Some(prestress);
    let mut sim = Simulation::new(m).unwrap();
    sim.run(|_, _| {}).unwrap();
    let last = sim.n_particles() - 1;
    assert!(sim.is_failed(last - 1) && sim.is_failed(last - 2));
    // Every particle still carrying stress has a surviving neighbour to carry it with.
    for i in 0..sim.n_particles() {
        let alive = sim
            .bonds()
            .neighbours_of(i)
            .iter()
            .any(|&j| !sim.is_failed(j as usize));
        if !sim.is_failed(i) {
            assert!(
                alive,
                "particle {i} has no surviving neighbour but has not failed"
            );
        } else {
            assert_eq!(sim.stresses()[i], Tensor3::zeros(), "particle {i}");
        }
    }
    assert!(sim.is_failed(last));
}
