//! Who may touch whom: the particles that take part in a contact, their current positions, and
//! a Verlet list of candidate partners in the current configuration (numerics.md §12), rebuilt
//! over a cell grid once a participant has moved half the skin. Also the deterministic chunked
//! sums, the scatter of forces into accelerations and the stiffness time-step vote that every
//! contact law shares. Knows nothing about the force law.

use rayon::prelude::*;
use tlsph_math::{PlaneReflections, Vector};
use tlsph_neighbours::CellGrid;

/// Participants per parallel task of the loops over participants (here and in the solver's
/// contact effects that gather per participant).
pub const PARTICIPANTS_PER_TASK: usize = 256;

/// Chunk length of the deterministic energy/force sums.
const CHUNK: usize = 4096;

/// A candidate partner seen through symmetry planes: participant `partner` reflected across
/// the planes of `mask` (bit k: plane k of the [`PlaneReflections`]). It stands for the
/// partner's mirror image in the full model, at M(x), moving with M v.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct ImagePartner {
    /// Participant index of the real partner.
    pub partner: u32,
    /// Planes it is reflected across (never 0).
    pub mask: u32,
}

/// A pair offered to the `accepts` test of [`ContactCandidates::refresh`] at a rebuild:
/// participant `j` (for `mask` 0) or its mirror image across the planes of `mask` lies within
/// the search radius of participant `k`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CandidateOffer {
    /// Participant index of the particle searched around.
    pub k: usize,
    /// Its particle index.
    pub particle_k: usize,
    /// Its body.
    pub body_k: u32,
    /// Participant index of the partner offered.
    pub j: usize,
    /// Its particle index.
    pub particle_j: usize,
    /// Its body.
    pub body_j: u32,
    /// Planes the partner is seen across (0: the partner itself).
    pub mask: u32,
}

impl CandidateOffer {
    /// Whether the two particles belong to different bodies.
    #[inline]
    pub fn across_bodies(&self) -> bool {
        self.body_k != self.body_j
    }
}

/// Participants of a contact and their candidate partners (CSR, participant indices).
///
/// A participant is a particle whose body takes part; participants are numbered in ascending
/// particle order, and every per-participant array of a contact law uses that numbering.
///
/// With symmetry planes ([`Self::with_mirrors`]) the list also holds, per participant, the
/// mirror images of participants within reach ([`Self::images_of`]): the full model's
/// particles beyond the planes, which a contact at a plane touches (numerics.md §13.1).
/// Without planes nothing is allocated for them.
#[derive(Debug, Clone)]
pub struct ContactCandidates<const D: usize> {
    /// Particle index of each participant (ascending).
    participants: Vec<u32>,
    /// Participant index of each particle (`u32::MAX` if it takes no part).
    local: Vec<u32>,
    /// Body of each participant.
    body: Vec<u32>,
    /// Body whose contact force is reported as the resultant: the lowest-index participant's.
    reported_body: u32,
    /// Verlet skin \[m\]: a rebuild follows once a participant has moved half of it.
    skin: f64,
    /// Candidate search radius (interaction reach + skin) \[m\].
    radius: f64,
    /// Current positions of the participants.
    positions: Vec<Vector<D>>,
    positions_at_build: Vec<Vector<D>>,
    offsets: Vec<usize>,
    candidates: Vec<u32>,
    /// Symmetry planes (empty: no images).
    mirrors: PlaneReflections<D>,
    /// Image candidates (CSR; empty without planes).
    image_offsets: Vec<usize>,
    images: Vec<ImagePartner>,
    rebuilds: u64,
    /// Per-chunk (energy, force on the reported body).
    chunk_sums: Vec<(f64, Vector<D>)>,
}

impl<const D: usize> ContactCandidates<D> {
    /// Participants: the particles whose body (`body_of`, one entry per particle) satisfies
    /// `takes_part`; candidates are searched within `reach + skin`.
    pub fn new(body_of: &[u32], takes_part: impl Fn(u32) -> bool, reach: f64, skin: f64) -> Self {
        let mut local = vec![u32::MAX; body_of.len()];
        let mut participants = Vec::new();
        let mut body = Vec::new();
        for (i, &b) in body_of.iter().enumerate() {
            if takes_part(b) {
                local[i] = participants.len() as u32;
                participants.push(i as u32);
                body.push(b);
            }
        }
        let n = participants.len();
        Self {
            reported_body: body.first().copied().unwrap_or(0),
            participants,
            local,
            body,
            skin,
            radius: reach + skin,
            positions: vec![Vector::zeros(); n],
            positions_at_build: Vec::new(),
            offsets: Vec::with_capacity(n + 1),
            candidates: Vec::new(),
            mirrors: PlaneReflections::default(),
            image_offsets: Vec::new(),
            images: Vec::new(),
            rebuilds: 0,
            chunk_sums: Vec::with_capacity(n.div_ceil(CHUNK)),
        }
    }

    /// The same list, also searching the mirror images of the participants across the
    /// symmetry planes `mirrors` (every body on the same side of every plane).
    pub fn with_mirrors(mut self, mirrors: PlaneReflections<D>) -> Self {
        if !mirrors.is_empty() {
            self.image_offsets.reserve(self.participants.len() + 1);
        }
        self.mirrors = mirrors;
        self
    }

    /// The symmetry planes of the images.
    pub fn mirrors(&self) -> &PlaneReflections<D> {
        &self.mirrors
    }

    /// Number of participants.
    pub fn len(&self) -> usize {
        self.participants.len()
    }

    /// Whether no particle takes part.
    pub fn is_empty(&self) -> bool {
        self.participants.is_empty()
    }

    /// Particle index of each participant.
    pub fn participants(&self) -> &[u32] {
        &self.participants
    }

    /// Body of each participant.
    pub fn body(&self) -> &[u32] {
        &self.body
    }

    /// Verlet skin \[m\].
    pub fn skin(&self) -> f64 {
        self.skin
    }

    /// Current positions of the participants (as of the last [`Self::refresh`]).
    pub fn positions(&self) -> &[Vector<D>] {
        &self.positions
    }

    /// Candidate partners (participant indices, ascending) of participant `k`.
    #[inline]
    pub fn of(&self, k: usize) -> &[u32] {
        &self.candidates[self.offsets[k]..self.offsets[k + 1]]
    }

    /// Mirror images of participants that are candidate partners of participant `k`
    /// (ascending; empty without symmetry planes).
    #[inline]
    pub fn images_of(&self, k: usize) -> &[ImagePartner] {
        match self.image_offsets.get(k..k + 2) {
            Some(range) => &self.images[range[0]..range[1]],
            None => &[],
        }
    }

    /// Candidate-list rebuilds so far.
    pub fn rebuilds(&self) -> u64 {
        self.rebuilds
    }

    /// Reads the participants' positions x = X + u (`positions0` + `displacements`, one entry
    /// per particle) and rebuilds the candidate lists if any participant has moved more than
    /// half the skin since the last build (a NaN position counts as moved). `accepts` decides
    /// whether a [`CandidateOffer`] within the search radius is a candidate.
    pub fn refresh(
        &mut self,
        positions0: &[Vector<D>],
        displacements: &[Vector<D>],
        accepts: impl Fn(CandidateOffer) -> bool,
    ) {
        let parts = &self.participants;
        self.positions
            .par_iter_mut()
            .enumerate()
            .with_min_len(PARTICIPANTS_PER_TASK)
            .for_each(|(k, x)| {
                let i = parts[k] as usize;
                *x = positions0[i] + displacements[i];
            });
        let half_skin_sq = 0.25 * self.skin * self.skin;
        let stale = self.positions_at_build.len() != self.positions.len()
            || self
                .positions
                .par_iter()
                .zip(self.positions_at_build.par_iter())
                .any(|(x, x_b)| {
                    let moved = (x - x_b).norm_squared();
                    moved.is_nan() || moved > half_skin_sq
                });
        if stale {
            self.rebuild(accepts);
        }
    }

    /// Every accepted participant within the search radius, ascending, and every accepted
    /// image within it. Allocates only the cell grid (and the lists if they grow). Non-finite
    /// positions give no candidates (the caller reports the non-finite state).
    fn rebuild(&mut self, accepts: impl Fn(CandidateOffer) -> bool) {
        self.offsets.clear();
        self.candidates.clear();
        self.offsets.push(0);
        let with_images = !self.mirrors.is_empty();
        self.image_offsets.clear();
        self.images.clear();
        if with_images {
            self.image_offsets.push(0);
        }
        let n = self.positions.len();
        if let Ok(grid) = CellGrid::new(&self.positions, self.radius) {
            let (r, r2) = (self.radius, self.radius * self.radius);
            for (k, x) in self.positions.iter().enumerate() {
                let start = self.candidates.len();
                let offer = |j: u32, mask: u32| CandidateOffer {
                    k,
                    particle_k: self.participants[k] as usize,
                    body_k: self.body[k],
                    j: j as usize,
                    particle_j: self.participants[j as usize] as usize,
                    body_j: self.body[j as usize],
                    mask,
                };
                grid.for_each_candidate_with_position(x, |j, xj| {
                    if (xj - x).norm_squared() < r2 && accepts(offer(j, 0)) {
                        self.candidates.push(j);
                    }
                });
                self.candidates[start..].sort_unstable();
                self.offsets.push(self.candidates.len());
                if !with_images {
                    continue;
                }
                // |M(x_j) − x_k| = |x_j − M(x_k)|: search around k's image. Only a participant
                // within the radius of every plane of a mask has partners across them.
                let start = self.images.len();
                for mask in self.mirrors.masks() {
                    if !self.mirrors.within(x, mask, r) {
                        continue;
                    }
                    let y = self.mirrors.point(x, mask);
                    grid.for_each_candidate_with_position(&y, |j, xj| {
                        if (xj - y).norm_squared() < r2 && accepts(offer(j, mask)) {
                            self.images.push(ImagePartner { partner: j, mask });
                        }
                    });
                }
                self.images[start..].sort_unstable();
                self.image_offsets.push(self.images.len());
            }
        } else {
            self.offsets.resize(n + 1, 0);
            if with_images {
                self.image_offsets.resize(n + 1, 0);
            }
        }
        self.positions_at_build.clone_from(&self.positions);
        self.rebuilds += 1;
    }

    /// (Σ energy over all participants, Σ force over the reported body's participants), each
    /// summed in fixed chunks so the result does not depend on the thread count. `energy` may
    /// be empty (sum 0).
    pub fn totals(&mut self, energy: &[f64], force: &[Vector<D>]) -> (f64, Vector<D>) {
        let (body, reported) = (&self.body, self.reported_body);
        (0..force.len().div_ceil(CHUNK))
            .into_par_iter()
            .map(|c| {
                let range = c * CHUNK..((c + 1) * CHUNK).min(force.len());
                let mut f = Vector::<D>::zeros();
                for k in range.clone() {
                    if body[k] == reported {
                        f += force[k];
                    }
                }
                let e = energy.get(range).map_or(0.0, |e| e.iter().sum::<f64>());
                (e, f)
            })
            .collect_into_vec(&mut self.chunk_sums);
        self.chunk_sums
            .iter()
            .fold((0.0, Vector::<D>::zeros()), |(e, f), (ce, cf)| {
                (e + ce, f + cf)
            })
    }

    /// Writes a = f / m for every participant into `out` (indexed by particle); other entries
    /// are left as they are.
    pub fn scatter_accelerations(
        &self,
        force: &[Vector<D>],
        masses: &[f64],
        out: &mut [Vector<D>],
    ) {
        let local = &self.local;
        out.par_iter_mut()
            .enumerate()
            .with_min_len(1024)
            .for_each(|(i, a)| {
                let k = local[i];
                if k != u32::MAX {
                    *a = force[k as usize] / masses[i];
                }
            });
    }

    /// Shortest stable step over the participants with positive stiffness `stiffness[k]`
    /// (numerics.md §7 `[C]`): min factor · sqrt(m_I / k_I) with the particle I, ties broken
    /// by the lower particle index (a total order, so the result does not depend on how the
    /// work is split).
    pub fn stiffness_time_step(
        &self,
        stiffness: &[f64],
        masses: &[f64],
        factor: f64,
    ) -> Option<(f64, usize)> {
        let parts = &self.participants;
        stiffness
            .par_iter()
            .enumerate()
            .with_min_len(PARTICIPANTS_PER_TASK)
            .filter(|(_, k)| **k > 0.0)
            .map(|(k, s)| {
                let i = parts[k] as usize;
                (factor * (masses[i] / s).sqrt(), i)
            })
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))
    }
}
