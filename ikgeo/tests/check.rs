//! `cargo test --release` in ikgeo/: the models in `models/` are what `src/model.rs` writes,
//! this crate's forward kinematics is ik-geo's, and over 1,000 random poses of each arm gcs
//! solves by circles and spheres, ik-geo's and gcs's solution sets agree (`gcs_ikgeo::check`);
//! for the two whose position chain is a quartic, gcs misses no solution ik-geo finds to machine
//! precision and gives no wrong one.

use gcs_ikgeo::arms::{
    self, ARMS, IRB6640, SPHERICAL_BOT, THREE_PARALLEL_BOT, TWO_PARALLEL_BOT, UR5,
};
use gcs_ikgeo::check::check;
use gcs_ikgeo::{
    ik_geo_robot, model, Irb6640, SphericalBot, ThreeParallelBot, TwoParallelBot, Ur5,
};

#[test]
fn the_models_are_what_the_writer_writes() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models");
    for arm in &ARMS {
        let path = dir.join(model::file_name(arm));
        let on_disk = std::fs::read_to_string(&path).expect("the model");
        assert!(
            on_disk == model::text(arm, &model::comment(arm)),
            "{} is stale: run `cargo run --release --bin write_models`",
            path.display()
        );
    }
}

#[test]
fn the_forward_kinematics_is_ik_geos() {
    for arm in &ARMS {
        let robot = ik_geo_robot(arm);
        for pose in arms::poses(arm, 100, 7) {
            let (r, t) = robot.fk(&pose.q);
            let d = (r - pose.r).amax().max((t - pose.t).amax());
            assert!(d < 1e-13, "{}: {d:e} at {:?}", arm.name, pose.q);
        }
    }
}

#[test]
fn gcs_and_ik_geo_find_the_same_solutions() {
    let reports = [check::<Ur5>(&UR5, 1000), check::<Irb6640>(&IRB6640, 1000)];
    for r in &reports {
        print!("{}", r.text());
    }
    for r in &reports {
        assert!(r.agrees(), "{}", r.text());
        assert_eq!(r.incomplete, 0, "{}", r.arm);
        assert_eq!(r.drawn_found, r.poses, "{}", r.arm);
    }
}

#[test]
fn the_quartic_and_searched_arms_miss_nothing_and_answer_nothing_wrong() {
    let reports = [
        check::<SphericalBot>(&SPHERICAL_BOT, 300),
        check::<ThreeParallelBot>(&THREE_PARALLEL_BOT, 300),
    ];
    for r in &reports {
        print!("{}", r.text());
        assert!(r.nothing_missed_or_wrong(), "{}", r.text());
        assert_eq!(r.incomplete, 0, "{}", r.arm);
    }
    // Searched: no list claims completeness, none is wrong, and the drawn arm is found at
    // nearly every pose.
    let r = check::<TwoParallelBot>(&TWO_PARALLEL_BOT, 100);
    print!("{}", r.text());
    assert!(r.nothing_missed_or_wrong(), "{}", r.text());
    assert_eq!(r.incomplete, r.poses, "{}", r.arm);
    assert!(r.drawn_found >= r.poses - 2, "{}", r.text());
}
