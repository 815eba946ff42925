//! Workspace criteria from the command line (`--criteria`, `--method`, `--wrench`,
//! `--wrench-box`, `--acceleration-box`, `--velocity`, and the method's options `--interior`,
//! `--alternating`, `--p`, `--alpha`), shared by `workspace`, `orientations`,
//! `dextrous` and `synthesize`: turned into the request's [`WorkspaceCriteria`] and checked
//! against the robot file by `cdpr-api` into a [`cdpr::api::CriteriaSetup`] that builds a pose evaluator at
//! any orientation.

use super::Numbers;
use cdpr::api::WorkspaceCriteria;
use cdpr::kinematics::CableModel;
use cdpr::tension::Method;

/// Workspace criteria and load, shared by `workspace`, `dextrous` and `synthesize`.
#[derive(clap::Args, Clone)]
pub struct CriteriaArgs {
    /// External wrench w_e on the platform (DOF numbers; default zero), e.g. --wrench 0,-10,0 for
    /// the thesis' load L1. The platform's gravity from the robot file is added.
    #[arg(long, allow_hyphen_values = true)]
    pub wrench: Option<Numbers>,
    /// Tension distribution method of the `tension` criterion: exact (n = DOF, eq. 6.12),
    /// closed-form (Alg. 6.1, n = DOF + 1), l1 (eq. 6.19), l2 (eq. 6.17), pinv (eq. 6.14: bounds
    /// only checked, smaller workspace), linf, improved-closed-form, barycenter, sotda, …
    /// Default: exact when n = DOF, else l2 (the thesis' workspace figures); synthesize: exact,
    /// closed-form or l1 (the thesis' constrained minimum ℓ1).
    #[arg(long)]
    pub method: Option<Method>,
    /// Comma list of criteria that must all hold: tension, length[:L] (m), det[:D],
    /// wrench-closure, capacity[:M], isotropic:F (N), stiffness:KT,KR (N/m, N·m/rad) or
    /// stiffness:K, interference[:D] (m) (see `cdpr workspace --help`). Default: tension, plus
    /// length and det when the robot file gives their limits.
    #[arg(long, value_name = "LIST")]
    pub criteria: Option<String>,
    /// Half-widths of the required wrench box of the `capacity` criterion (DOF numbers ≥ 0),
    /// centred on the external wrench.
    #[arg(long, allow_hyphen_values = true)]
    pub wrench_box: Option<Numbers>,
    /// Half-widths A_i of the acceleration box of the `dynamic` criterion (DOF numbers ≥ 0,
    /// m/s² and rad/s², centred on 0): every acceleration in it must be balanced within the
    /// bounds (needs the platform's mass, and `inertia` for planar/spatial platforms).
    #[arg(long, allow_hyphen_values = true)]
    pub acceleration_box: Option<Numbers>,
    /// The twist ẋ of the `dynamic` criterion (DOF numbers, m/s and rad/s; default 0).
    #[arg(long, allow_hyphen_values = true, requires = "acceleration_box")]
    pub velocity: Option<Numbers>,
    /// `--cable-model`: the `tension` and `capacity` criteria with elastic or sagging cables.
    #[command(flatten)]
    pub cable: super::cable_model::CableModelArgs,
    /// `--interior`, `--alternating`, `--p`, `--alpha`: the options of the `tension`
    /// criterion's method, as `cdpr tension` takes them.
    #[command(flatten)]
    pub peer: super::tension::PeerOptions,
}

impl CriteriaArgs {
    /// The criteria of a request.
    pub fn to_request(&self) -> WorkspaceCriteria {
        let v = |n: &Option<Numbers>| n.as_ref().map(|n| n.0.clone());
        WorkspaceCriteria {
            criteria: self.criteria.clone(),
            method: self.method,
            wrench: v(&self.wrench),
            wrench_box: v(&self.wrench_box),
            acceleration_box: v(&self.acceleration_box),
            velocity: v(&self.velocity),
            cable_model: match self.cable.model() {
                CableModel::Straight => None,
                m => Some(m.name().into()),
            },
            peer: self.peer.to_api(),
        }
    }
}
