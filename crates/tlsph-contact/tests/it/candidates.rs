//! The candidate list against brute force, its skin rule, non-finite positions, and the
//! deterministic sums and time-step vote across thread counts.

use rayon::ThreadPoolBuilder;
use tlsph_contact::{CandidateOffer, ContactCandidates, ImagePartner, PlaneReflections, Vector};

/// Deterministic points: two 2D blocks of `side`² jittered particles (bodies 0 and 1) facing
/// each other across a gap, and a third body (2) that takes no part.
fn scene(side: usize) -> (Vec<Vector<2>>, Vec<u32>) {
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut jitter = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 0.2 - 0.1
    };
    let mut points = Vec::new();
    let mut body = Vec::new();
    for (b, x0) in [
        (0u32, 0.0),
        (1, side as f64 - 0.5),
        (2, -(side as f64) - 5.0),
    ] {
        for i in 0..side {
            for j in 0..side {
                points.push(Vector::<2>::new(
                    x0 + i as f64 + jitter(),
                    j as f64 + jitter(),
                ));
                body.push(b);
            }
        }
    }
    (points, body)
}

fn cross_body(pair: CandidateOffer) -> bool {
    pair.across_bodies()
}

#[test]
fn candidates_are_every_cross_body_pair_within_reach_plus_skin() {
    let (points, body) = scene(12);
    let displacements = vec![Vector::zeros(); points.len()];
    let (reach, skin) = (1.0, 0.5);
    let mut list = ContactCandidates::new(&body, |b| b < 2, reach, skin);
    list.refresh(&points, &displacements, cross_body);
    assert_eq!(list.len(), 2 * 144);
    assert_eq!(list.rebuilds(), 1);
    let parts = list.participants();
    let mut pairs = 0;
    for k in 0..list.len() {
        let x = points[parts[k] as usize];
        let expected: Vec<u32> = (0..list.len() as u32)
            .filter(|&j| {
                let y = points[parts[j as usize] as usize];
                list.body()[j as usize] != list.body()[k]
                    && (y - x).norm_squared() < (reach + skin) * (reach + skin)
            })
            .collect();
        assert_eq!(list.of(k), expected.as_slice(), "participant {k}");
        pairs += expected.len();
    }
    assert!(
        pairs > 20,
        "the blocks face each other across the gap ({pairs} pairs)"
    );
}

#[test]
fn with_symmetry_planes_the_images_within_reach_are_listed_as_brute_force_finds_them() {
    // Quarter model: the planes x = −0.5 and y = −0.45 bound the scene's blocks (x ≥ −0.1,
    // y ≥ −0.1, jittered); a participant near a plane meets the images of the other body's
    // participants across it, and near both planes the corner images too.
    let (points, body) = scene(8);
    let displacements = vec![Vector::zeros(); points.len()];
    let (reach, skin) = (1.0, 0.5);
    let radius2 = (reach + skin) * (reach + skin);
    let mirrors = PlaneReflections::<2>::new([(0, -0.5), (1, -0.45)]).unwrap();
    let mut list =
        ContactCandidates::new(&body, |b| b < 2, reach, skin).with_mirrors(mirrors.clone());
    // Self-images too (the same body), to reach the corner images of the first block.
    list.refresh(&points, &displacements, |_| true);
    let parts = list.participants();
    let mut per_mask = [0usize; 4];
    for k in 0..list.len() {
        let x = points[parts[k] as usize];
        let mut expected = Vec::new();
        for j in 0..list.len() as u32 {
            for mask in 1..4 {
                let y = mirrors.point(&points[parts[j as usize] as usize], mask);
                if (y - x).norm_squared() < radius2 {
                    expected.push(ImagePartner { partner: j, mask });
                    per_mask[mask as usize] += 1;
                }
            }
        }
        expected.sort_unstable();
        assert_eq!(list.images_of(k), expected.as_slice(), "participant {k}");
    }
    assert!(
        per_mask[1..].iter().all(|&n| n > 0),
        "images across each plane and the corner: {per_mask:?}"
    );
    // Without planes no image is listed.
    let mut plain = ContactCandidates::new(&body, |b| b < 2, reach, skin);
    plain.refresh(&points, &displacements, |_| true);
    assert!((0..plain.len()).all(|k| plain.images_of(k).is_empty()));
    assert_eq!(
        (0..plain.len()).map(|k| plain.of(k)).collect::<Vec<_>>(),
        (0..list.len()).map(|k| list.of(k)).collect::<Vec<_>>(),
        "the planes leave the real candidates alone"
    );
}

#[test]
fn the_list_is_rebuilt_only_once_a_participant_has_moved_half_the_skin() {
    let (points, body) = scene(6);
    let mut displacements = vec![Vector::zeros(); points.len()];
    let mut list = ContactCandidates::new(&body, |b| b < 2, 1.0, 0.5);
    list.refresh(&points, &displacements, cross_body);
    // 0.24 < skin/2 = 0.25: positions follow, the list stays.
    displacements[40] = Vector::<2>::new(-0.24, 0.0);
    list.refresh(&points, &displacements, cross_body);
    assert_eq!(list.rebuilds(), 1);
    assert_eq!(list.positions()[40], points[40] + displacements[40]);
    displacements[40] = Vector::<2>::new(-0.26, 0.0);
    list.refresh(&points, &displacements, cross_body);
    assert_eq!(list.rebuilds(), 2);
    // A non-finite position forces a rebuild and yields no candidates, never a panic.
    displacements[3] = Vector::<2>::new(f64::NAN, 0.0);
    list.refresh(&points, &displacements, cross_body);
    assert_eq!(list.rebuilds(), 3);
    assert!((0..list.len()).all(|k| list.of(k).is_empty()));
}

#[test]
fn sums_and_time_step_vote_are_identical_for_any_thread_count() {
    let (points, body) = scene(70);
    let displacements = vec![Vector::zeros(); points.len()];
    let run = |threads: usize| {
        ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                let mut list = ContactCandidates::new(&body, |b| b < 2, 1.0, 0.5);
                list.refresh(&points, &displacements, cross_body);
                let n = list.len();
                let energy: Vec<f64> = (0..n).map(|k| 1.0 / (1.0 + k as f64)).collect();
                let force: Vec<Vector<2>> = (0..n)
                    .map(|k| Vector::<2>::new((k as f64).sin(), 1e-3 * k as f64))
                    .collect();
                let masses: Vec<f64> = (0..points.len()).map(|i| 1.0 + (i % 7) as f64).collect();
                let stiffness: Vec<f64> = (0..n).map(|k| [0.0, 2.0, 8.0][k % 3]).collect();
                let totals = list.totals(&energy, &force);
                let vote = list.stiffness_time_step(&stiffness, &masses, 0.5);
                let mut out = vec![Vector::<2>::zeros(); points.len()];
                list.scatter_accelerations(&force, &masses, &mut out);
                (totals, vote, out, n)
            })
    };
    let (one, four) = (run(1), run(4));
    assert_eq!(one.0 .0.to_bits(), four.0 .0.to_bits());
    assert_eq!(one.0 .1, four.0 .1);
    assert_eq!(one.1, four.1);
    assert_eq!(one.2, four.2);
    // The resultant is the force on body 0 (the lowest-index participant's body), the energy
    // the sum over all participants.
    let n = one.3;
    let expected: f64 = (0..n / 2).map(|k| (k as f64).sin()).sum();
    assert!((one.0 .1[0] - expected).abs() < 1e-9);
    let energy: f64 = (0..n).map(|k| 1.0 / (1.0 + k as f64)).sum();
    assert!((one.0 .0 - energy).abs() < 1e-12);
    // Vote: stiffness 8 on the lightest particle: 0.5 sqrt(1/8), ties to the lowest index.
    let (dt, particle) = one.1.unwrap();
    assert_eq!(dt, 0.5 * (1.0f64 / 8.0).sqrt());
    assert_eq!(
        particle, 14,
        "first participant with stiffness 8 (k % 3 = 2) and mass 1"
    );
    // Particles of the non-participating body keep their entries.
    assert!(one.2[2 * 4900..].iter().all(|a| *a == Vector::<2>::zeros()));
}
