//! The four arms of ik-geo 0.1.2's `robot` module (`ur5()`, `irb6640()`, `spherical_bot()`,
//! `three_parallel_bot()`), as their `get_kin()` in `src/inverse_kinematics/hardcoded/setups.rs`
//! writes them: product of exponentials, joint axes `h` (3x6) and offsets `p` (3x7). Joint `i`
//! (0-based here) turns about `h[i]` through the point `p[0] + ... + p[i]` of the zero
//! configuration; the tool is at the sum of all seven `p`, and its frame is the base's at
//! q = 0 (ik-geo's `Kinematics::forward_kinematics`: `r = r * rot(h_i, q_i); p += r * p_{i+1}`).
//!
//! The numbers are copied here, and the forward kinematics below is written here: neither
//! calls ik-geo nor gcs (`tests/models.rs` checks it against ik-geo's own `fk`).

use ik_geo::nalgebra::{Matrix3, Rotation3, Unit, Vector3};

/// One of ik-geo's arms: its kinematics, the ik-geo constructor that solves it, and the joint
/// angles its `.gcs` model is sketched at.
#[derive(Debug, Clone, Copy)]
pub struct Arm {
    /// ik-geo's name of the arm (its function in `ik_geo::robot`).
    pub name: &'static str,
    /// The joint axes, `h` of ik-geo's `Kinematics`, one column a joint.
    pub h: [[f64; 3]; 6],
    /// The offsets, `p` of ik-geo's `Kinematics`: base to joint 1, joint i to i + 1, 6 to tool.
    pub p: [[f64; 3]; 7],
    /// The joint angles of the model's sketch: a bent elbow and wrist, no two consecutive
    /// axes parallel that are not always so. The sketch's branches are what `solve` follows.
    pub sketch: [f64; 6],
}

const Z: [f64; 3] = [0.0, 0.0, 0.0];
const EX: [f64; 3] = [1.0, 0.0, 0.0];
const EY: [f64; 3] = [0.0, 1.0, 0.0];
const EZ: [f64; 3] = [0.0, 0.0, 1.0];
const NEG_EZ: [f64; 3] = [0.0, 0.0, -1.0];

/// `Ur5::get_kin()`: three parallel axes and the last two meeting
/// (`Robot::three_parallel_two_intersecting`).
pub const UR5: Arm = Arm {
    name: "ur5",
    h: [EZ, EY, EY, EY, NEG_EZ, EY],
    p: [
        [0.0, 0.0, 0.089159],
        [0.0, 0.1358, 0.0],
        [0.425, -0.1197, 0.0],
        [0.3922, 0.0, 0.0],
        [0.0, 0.093, 0.0],
        [0.0, 0.0, -0.0946],
        [0.0, 0.0823, 0.0],
    ],
    sketch: [0.3, -0.7, 1.1, -0.5, 0.8, 0.4],
};

/// `Irb6640::get_kin()`: a spherical wrist and two parallel axes
/// (`Robot::spherical_two_parallel`).
pub const IRB6640: Arm = Arm {
    name: "irb6640",
    h: [EZ, EY, EY, EX, EY, EX],
    p: [
        Z,
        [0.32, 0.0, 0.78],
        [0.0, 0.0, 1.075],
        [1.1425, 0.0, 0.2],
        Z,
        Z,
        [0.2, 0.0, 0.0],
    ],
    sketch: [0.3, 0.4, -0.6, 0.5, 0.9, -0.3],
};

/// `SphericalBot::get_kin()`: a spherical wrist, the first three axes in general position
/// (`Robot::spherical`, IK-Geo's subproblem 5).
pub const SPHERICAL_BOT: Arm = Arm {
    name: "spherical_bot",
    h: [EY, EZ, EY, EX, EY, EX],
    p: [
        Z,
        [1.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        Z,
        Z,
        [1.0, 0.0, 0.0],
    ],
    sketch: [0.3, 0.5, -0.6, 0.5, 0.9, -0.3],
};

/// `ThreeParallelBot::get_kin()`: three parallel axes and no two axes meeting
/// (`Robot::three_parallel`, IK-Geo's subproblem 6).
pub const THREE_PARALLEL_BOT: Arm = Arm {
    name: "three_parallel_bot",
    h: [EZ, EX, EX, EX, EZ, EX],
    p: [EZ, EY, EY, EY, EY, [1.0, 1.0, 0.0], EX],
    sketch: [0.3, -0.7, 1.1, -0.5, 0.8, 0.4],
};

/// `TwoParallelBot::get_kin()`: two parallel axes and otherwise general, with no closed form
/// (`Robot::two_parallel`, ik-geo's search over the base's angle).
pub const TWO_PARALLEL_BOT: Arm = Arm {
    name: "two_parallel_bot",
    h: [
        EZ,
        EX,
        EX,
        EZ,
        EX,
        [
            std::f64::consts::FRAC_1_SQRT_2,
            0.0,
            std::f64::consts::FRAC_1_SQRT_2,
        ],
    ],
    p: [EZ, EY, EY, EY, EY, EY, EZ],
    sketch: [0.3, -0.7, 1.1, -0.5, 0.8, 0.4],
};

/// The five arms, in the order the bench and the check report them.
pub const ARMS: [Arm; 5] = [
    UR5,
    IRB6640,
    SPHERICAL_BOT,
    THREE_PARALLEL_BOT,
    TWO_PARALLEL_BOT,
];

/// A vector of nalgebra (ik-geo's version) from an array.
pub fn v(a: [f64; 3]) -> Vector3<f64> {
    Vector3::new(a[0], a[1], a[2])
}

/// A rigid motion: a point `x` goes to `r * x + t`.
#[derive(Debug, Clone, Copy)]
pub struct Motion {
    /// The rotation.
    pub r: Matrix3<f64>,
    /// The translation.
    pub t: Vector3<f64>,
}

impl Motion {
    /// Where the motion takes point `x`.
    pub fn point(&self, x: Vector3<f64>) -> Vector3<f64> {
        self.r * x + self.t
    }
}

/// A turn by `angle` about the unit axis `h`, counter-clockwise looking down `h` (ik-geo's
/// `rot`, Rodrigues' formula).
pub fn turn(h: Vector3<f64>, angle: f64) -> Matrix3<f64> {
    Rotation3::from_axis_angle(&Unit::new_normalize(h), angle).into_inner()
}

/// A unit vector square to the unit vector `h`: the axis of the frame least along `h`, made
/// square to it.
pub fn square_to(h: Vector3<f64>) -> Vector3<f64> {
    let k = (0..3)
        .min_by(|&a, &b| h[a].abs().total_cmp(&h[b].abs()))
        .unwrap_or(0);
    let e = Vector3::ith(k, 1.0);
    (e - h.dot(&e) * h).normalize()
}

impl Arm {
    /// Joint `i`'s axis.
    pub fn axis(&self, i: usize) -> Vector3<f64> {
        v(self.h[i])
    }

    /// Joint `i`'s point in the zero configuration: `p[0] + ... + p[i]`.
    pub fn origin(&self, i: usize) -> Vector3<f64> {
        self.p[..=i].iter().map(|&p| v(p)).sum()
    }

    /// The tool's point in the zero configuration: the sum of all of `p`.
    pub fn tool(&self) -> Vector3<f64> {
        self.origin(6)
    }

    /// The motion of each link (1 to 6, the tool's link last) from the zero configuration at
    /// joint angles `q`: the product of the exponentials of the joints' screws.
    pub fn links(&self, q: &[f64; 6]) -> [Motion; 6] {
        let mut out = [Motion {
            r: Matrix3::identity(),
            t: Vector3::zeros(),
        }; 6];
        let (mut r, mut t) = (Matrix3::identity(), Vector3::zeros());
        for i in 0..6 {
            // exp(xi_i q_i): a turn about the axis through the joint's point.
            let c = self.origin(i);
            let turn = turn(self.axis(i), q[i]);
            t += r * (c - turn * c);
            r *= turn;
            out[i] = Motion { r, t };
        }
        out
    }

    /// The tool's pose at joint angles `q`: its rotation (the base's frame at q = 0) and point.
    pub fn pose(&self, q: &[f64; 6]) -> (Matrix3<f64>, Vector3<f64>) {
        let m = self.links(q)[5];
        (m.r, m.point(self.tool()))
    }

    /// Joint angles from each link's rotation (in the zero configuration's sense: link `i`'s
    /// rotation from the zero configuration), the angle of link `i` relative to link `i - 1`
    /// about joint `i`'s axis, wrapped to (-pi, pi]; and how far each relative rotation is from
    /// a turn about that axis (the largest over the joints).
    pub fn angles(&self, rotations: &[Matrix3<f64>; 6]) -> ([f64; 6], f64) {
        let mut q = [0.0; 6];
        let mut off = 0.0f64;
        let mut before = Matrix3::identity();
        for i in 0..6 {
            let m: Matrix3<f64> = before.transpose() * rotations[i];
            let h = self.axis(i);
            off = off.max((m * h - h).norm());
            let u = square_to(h);
            let mu = m * u;
            q[i] = wrap(h.dot(&u.cross(&mu)).atan2(u.dot(&mu)));
            before = rotations[i];
        }
        (q, off)
    }
}

/// An angle wrapped to (-pi, pi].
pub fn wrap(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let w = a.rem_euclid(TAU);
    if w > PI {
        w - TAU
    } else {
        w
    }
}

/// The largest difference between two sets of joint angles, each difference wrapped to
/// (-pi, pi].
pub fn angle_distance(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| wrap(x - y).abs())
        .fold(0.0, f64::max)
}

/// A small xorshift generator, so that every run draws the same poses.
#[derive(Debug, Clone)]
pub struct Rng(pub u64);

impl Rng {
    /// A number in [0, 1).
    pub fn unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// An angle in [-pi, pi).
    pub fn angle(&mut self) -> f64 {
        (2.0 * self.unit() - 1.0) * std::f64::consts::PI
    }
}

/// A pose of the tool, drawn from joint angles.
#[derive(Debug, Clone, Copy)]
pub struct Pose {
    /// The joint angles it was drawn from.
    pub q: [f64; 6],
    /// The tool's rotation.
    pub r: Matrix3<f64>,
    /// The tool's point.
    pub t: Vector3<f64>,
}

impl Pose {
    /// The nine params of the `.gcs` target marker: the point, the z axis, the x axis.
    pub fn params(&self) -> [f64; 9] {
        let (z, x) = (self.r.column(2), self.r.column(0));
        [
            self.t.x, self.t.y, self.t.z, z[0], z[1], z[2], x[0], x[1], x[2],
        ]
    }
}

/// `n` poses of `arm` from random joint angles (uniform in [-pi, pi)), the same for a seed.
pub fn poses(arm: &Arm, n: usize, seed: u64) -> Vec<Pose> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| {
            let q = std::array::from_fn(|_| rng.angle());
            let (r, t) = arm.pose(&q);
            Pose { q, r, t }
        })
        .collect()
}
