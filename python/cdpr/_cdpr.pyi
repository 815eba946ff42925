"""Type stubs of the native module cdpr._cdpr (see the docstrings for units and meanings)."""

from os import PathLike
from typing import Any, Dict, List, Literal, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
FloatArray = npt.NDArray[np.float64]
BoolArray = npt.NDArray[np.bool_]
IntArray = npt.NDArray[np.int64]
Motion = Literal["point2", "planar", "point3", "spatial"]

METHODS: List[str]
__version__: str

def thread_count() -> int: ...
def calibrate(
    robot: "Robot",
    samples: ArrayLike,
    known_poses: Optional[ArrayLike] = None,
    *,
    unknowns: str = "frame,offsets",
    relative: bool = False,
    reference: Optional[List[float]] = None,
) -> Dict[str, Any]: ...

class KinematicsResult:
    lengths: FloatArray
    unit_vectors: FloatArray
    wrench_matrix: FloatArray
    attachment_points: FloatArray

class ForwardResult:
    pose: FloatArray
    residual: Union[FloatArray, float]
    iterations: Union[IntArray, int]
    converged: Union[BoolArray, bool]
    status: Union[List[str], str]
    min_singular_value: Union[FloatArray, float]
    solutions: Optional[FloatArray]
    residual_rms: Union[FloatArray, float]
    pose_std: FloatArray

class TensionResult:
    tensions: FloatArray
    feasible: Union[BoolArray, bool]
    residual: Union[FloatArray, float]
    reason: Union[List[Optional[str]], Optional[str]]
    external_wrench: FloatArray
    method: str

class CapacityResult:
    capacity_margin: Union[FloatArray, float]
    feasible: Union[BoolArray, bool]
    limiting_facet: Union[IntArray, int]

class IsotropicResult:
    isotropic_force: Union[FloatArray, float]
    wrench_radius: Union[FloatArray, float]
    definition: str
    vertices: Optional[FloatArray]
    faces: Optional[List[IntArray]]
    normals: Optional[FloatArray]
    offsets: Optional[FloatArray]

class StiffnessResult:
    stiffness: FloatArray
    passive: FloatArray
    active: FloatArray

class WorkspaceResult:
    feasible: Optional[BoolArray]
    x: Optional[FloatArray]
    y: Optional[FloatArray]
    z: Optional[FloatArray]
    points: Optional[FloatArray]
    boundaries: Optional[List[FloatArray]]
    vertices: Optional[FloatArray]
    faces: Optional[IntArray]
    surface_area: Optional[float]
    area: float
    area_cells: Optional[float]
    area_points: Optional[float]
    volume_convention: Optional[str]
    volume: Optional[float]
    cell_area: Optional[float]
    feasible_points: Optional[int]
    total_points: Optional[int]
    criteria: List[str]
    method: str
    external_wrench: FloatArray
    box: List[float]

class TrajectoryResult:
    s: FloatArray
    poses: FloatArray
    tensions: FloatArray
    feasible: BoolArray
    reason: List[Optional[str]]
    max_jump: FloatArray
    discontinuities: List[int]
    feasible_count: int
    method: str

class TimedTrajectoryResult:
    t: FloatArray
    poses: FloatArray
    velocity: FloatArray
    acceleration: FloatArray
    cable_lengths: FloatArray
    cable_speeds: FloatArray
    cable_accelerations: FloatArray
    tensions: FloatArray
    feasible: BoolArray
    reason: List[Optional[str]]
    feasible_count: int
    inertial_wrench: Optional[FloatArray]
    motor_speeds: Optional[FloatArray]
    motor_torques: Optional[FloatArray]
    motor_powers: Optional[FloatArray]
    motors_within_limits: Optional[bool]
    motor_limit_violations: Optional[List[str]]
    waypoint_times: List[float]
    duration: float
    dt: float
    time_law: str
    method: str
    dynamics: bool

class SimulationResult:
    t: FloatArray
    poses: FloatArray
    velocities: FloatArray
    accelerations: FloatArray
    tensions: FloatArray
    steps: int
    rejected_steps: int
    integrator: str

class Robot:
    @staticmethod
    def load(path: Union[str, PathLike[str]], cable_set: Optional[str] = None) -> Robot: ...
    @staticmethod
    def from_toml(text: str, file: str = "<string>") -> Robot: ...
    def to_toml(self, header: str = "") -> str: ...
    @staticmethod
    def from_anchors(
        motion: Motion,
        frame: ArrayLike,
        platform: Optional[ArrayLike] = None,
        t_min: Optional[ArrayLike] = None,
        t_max: Optional[ArrayLike] = None,
        *,
        mass: float = 0.0,
        centre_of_mass: Optional[ArrayLike] = None,
        gravity: Optional[ArrayLike] = None,
        axial_stiffness: Optional[ArrayLike] = None,
        min_cable_length: Optional[float] = None,
        min_jacobian_det: Optional[float] = None,
        name: str = "robot",
    ) -> Robot: ...
    @property
    def dof(self) -> int: ...
    @property
    def n_cables(self) -> int: ...
    @property
    def motion(self) -> Motion: ...
    @property
    def name(self) -> str: ...
    @property
    def frame(self) -> FloatArray: ...
    @property
    def platform(self) -> FloatArray: ...
    @property
    def t_min(self) -> FloatArray: ...
    @property
    def t_max(self) -> FloatArray: ...
    @property
    def mass(self) -> float: ...
    @property
    def gravity(self) -> FloatArray: ...
    @property
    def centre_of_mass(self) -> FloatArray: ...
    @property
    def axial_stiffness(self) -> Optional[FloatArray]: ...
    @property
    def min_cable_length(self) -> Optional[float]: ...
    @property
    def min_jacobian_det(self) -> Optional[float]: ...
    @property
    def warnings(self) -> List[str]: ...
    def gravity_wrench(self, poses: ArrayLike) -> FloatArray: ...
    def inverse_kinematics(
        self, poses: ArrayLike, *, out: Optional[KinematicsResult] = None
    ) -> KinematicsResult: ...
    def forward_kinematics(
        self,
        lengths: ArrayLike,
        guess: Optional[ArrayLike] = None,
        *,
        tolerance: float = 1e-9,
        max_iterations: int = 100,
        length_sigma: float = 1e-4,
    ) -> ForwardResult: ...
    def tensions(
        self,
        poses: ArrayLike,
        wrenches: Optional[ArrayLike] = None,
        method: str = "l2",
        *,
        direction: Optional[Sequence[float]] = None,
        nu: float = 1.0,
        sotda_search: Literal["corners", "vertices", "full"] = "corners",
    ) -> TensionResult: ...
    def capacity_margin(
        self,
        poses: ArrayLike,
        wrenches: Optional[ArrayLike] = None,
        *,
        wrench_box: Optional[Sequence[float]] = None,
        wrench_ball: Optional[float] = None,
    ) -> CapacityResult: ...
    def isotropic_force(self, poses: ArrayLike, wrenches: Optional[ArrayLike] = None) -> IsotropicResult: ...
    def stiffness(
        self,
        poses: ArrayLike,
        tensions: ArrayLike,
        axial_stiffness: Optional[ArrayLike] = None,
    ) -> StiffnessResult: ...
    def workspace(
        self,
        resolution: Optional[int] = None,
        box: Optional[Sequence[float]] = None,
        orientation: Union[float, Sequence[float], None] = None,
        criteria: Union[str, Sequence[str], None] = None,
        method: Optional[str] = None,
        wrench: Optional[Sequence[float]] = None,
        wrench_box: Optional[Sequence[float]] = None,
        boundary: Literal["grid", "chord", "mesh"] = "grid",
        chord: float = 0.05,
        volume_convention: Literal["cells", "points"] = "cells",
    ) -> WorkspaceResult: ...
    def trajectory(
        self,
        waypoints: Optional[ArrayLike] = None,
        samples: Optional[int] = None,
        step: Optional[float] = None,
        wrenches: Optional[ArrayLike] = None,
        method: str = "l2",
        *,
        direction: Optional[Sequence[float]] = None,
        nu: float = 1.0,
        sotda_search: Literal["corners", "vertices", "full"] = "corners",
        jump_ratio: float = 20.0,
        time_law: Optional[
            Literal["linear", "cubic", "quintic", "trapezoid", "parabolic-blend"]
        ] = None,
        duration: Optional[float] = None,
        dt: Optional[float] = None,
        times: Optional[Sequence[float]] = None,
        max_velocity: Optional[float] = None,
        max_acceleration: Optional[float] = None,
        blend_time: Optional[float] = None,
        dynamics: bool = False,
        cable_model: Literal["straight", "elastic", "catenary"] = "straight",
        interior: Optional[Literal["icf", "cf"]] = None,
        alternating: bool = False,
        p: Optional[float] = None,
        alpha: Optional[float] = None,
        caspr_trajectory: Optional[Union[str, PathLike]] = None,
        trajectory_id: Optional[str] = None,
    ) -> Union[TrajectoryResult, TimedTrajectoryResult]: ...
    def simulate(
        self,
        start: Sequence[float],
        duration: float,
        dt: float,
        *,
        velocity: Optional[Sequence[float]] = None,
        tensions: Optional[Sequence[float]] = None,
        tension_profile: Optional[Tuple[ArrayLike, ArrayLike]] = None,
        unstrained_lengths: Optional[Sequence[float]] = None,
        damping: float = 0.0,
        integrator: Literal["rk4", "rk45"] = "rk4",
        tolerance: float = 1e-9,
        wrench: Optional[Sequence[float]] = None,
    ) -> SimulationResult: ...
    def mass_matrix(self, poses: ArrayLike) -> FloatArray: ...
