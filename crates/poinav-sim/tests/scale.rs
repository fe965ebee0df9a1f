//! Simulation at scale: a 200-robot scenario gives byte-identical traces and summaries on 1, 2
//! and 4 threads; `trace every N` keeps exactly every N-th step of the full trace; a run
//! without a trace has the same summary, expectations and plots as one with it; the trace
//! streamed to a file equals the one kept in memory; a crowd at the single-lane doors decides
//! as it did before the door check used the robot grid.

use std::path::Path;

use poinav_bridge::prepare;
use poinav_sim::{run, run_into, run_with, Outcome, Scenario, TraceOut};

/// 200 robots, five in each of the 40 rooms of a 20-rooms-per-side test building, each driving
/// to another room through the corridor (a C-1 zone): doors measured by many robots at once,
/// robots meeting, jams at the doors.
fn crowd() -> Scenario {
    let rooms = 20usize;
    let mut s = format!(
        "name = \"crowd\"\nduration_s = 4.0\n[building]\ndemo = {{ rooms_per_side = {rooms} }}\n"
    );
    let mut k = 0;
    for side in 0..2 {
        for i in 0..rooms {
            let x0 = i as f64 * 4.2;
            let y0 = if side == 0 { 0.0 } else { 6.8 };
            let heading = if side == 0 { 90.0 } else { -90.0 };
            for (dx, dy) in [(1.0, 1.0), (3.0, 1.0), (1.0, 3.0), (3.0, 3.0), (2.0, 2.0)] {
                k += 1;
                let room = side * rooms + i;
                let mut to = (room * 7 + 3 + k) % (2 * rooms);
                if to == room {
                    to = (to + 1) % (2 * rooms);
                }
                s.push_str(&format!(
                    "[[robot]]\nname = \"R{k}\"\nstart = {{ x = {}, y = {}, heading_deg = {heading} }}\ncontroller = {{ kind = \"route\", to = \"Room {}\" }}\n",
                    x0 + dx,
                    y0 + dy,
                    to + 1
                ));
            }
        }
    }
    s.push_str("[[expect]]\nkind = \"no-contact\"\n[[expect]]\nkind = \"speed-range\"\nrobot = \"R1\"\nreaches_m_s = 0.5\n");
    Scenario::from_toml(&s, "crowd.toml", Path::new(".")).unwrap()
}

fn summary(o: &Outcome) -> String {
    serde_json::to_string_pretty(&o.summary()).unwrap()
}

#[test]
fn two_hundred_robots_give_the_same_bytes_on_one_two_and_four_threads() {
    let s = crowd();
    let floor = prepare(&s, None).unwrap().floor().clone();
    let runs: Vec<Outcome> = [1, 2, 4]
        .into_iter()
        .map(|threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| run(&s, None, &floor).unwrap())
        })
        .collect();
    let trace = runs[0].trace.as_deref().unwrap();
    // 241 steps (4 s at 60 Hz, both ends) of 200 robots.
    assert_eq!(trace.iter().filter(|&&b| b == b'\n').count(), 241 * 200);
    for r in &runs[1..] {
        assert!(r.trace.as_deref().unwrap() == trace, "traces differ");
        assert_eq!(summary(r), summary(&runs[0]));
    }
    // The run is not trivial: robots moved, met and measured doors.
    let o = &runs[0];
    let moved = o.figures.iter().filter(|f| f.travelled > 1.0).count();
    assert!(moved > 100, "{moved} robots moved more than 1 m");
    let count = |kind: &str| o.events().iter().filter(|e| e.kind.tag() == kind).count();
    assert!(
        count("clearance") >= 20,
        "{} clearances",
        count("clearance")
    );
    assert!(
        count("robot-role") > 0,
        "robots met: {}",
        count("robot-role")
    );
}

#[test]
fn a_thinned_trace_keeps_every_nth_step_of_the_full_one() {
    let s = crowd();
    let floor = prepare(&s, None).unwrap().floor().clone();
    let full = run(&s, None, &floor).unwrap();
    let mut thin: Vec<u8> = Vec::new();
    let out = TraceOut {
        writer: &mut thin,
        every: 7,
        name: "thin".into(),
        format: poinav_sim::TraceFormat::Jsonl,
    };
    let thinned = run_with(&s, None, &floor, Some(out)).unwrap();
    let text = String::from_utf8(full.trace.clone().unwrap()).unwrap();
    let kept: String = text
        .lines()
        .filter(|l| {
            let v: serde_json::Value = serde_json::from_str(l).unwrap();
            v["step"].as_u64().unwrap() % 7 == 0
        })
        .map(|l| format!("{l}\n"))
        .collect();
    // Steps 0, 7, ..., 238: 35 steps of 200 robots.
    assert_eq!(kept.lines().count(), 35 * 200);
    assert!(String::from_utf8(thin).unwrap() == kept);
    assert_eq!(summary(&thinned), summary(&full));
}

#[test]
fn without_a_trace_summary_expectations_and_plots_are_unchanged() {
    let s = crowd();
    let floor = prepare(&s, None).unwrap().floor().clone();
    let with = tempfile::tempdir().unwrap();
    let without = tempfile::tempdir().unwrap();
    let (a, _) = run_into(with.path(), &s, None, &floor, Some(1)).unwrap();
    // A trace left by an earlier run is removed, not kept beside the new summary.
    std::fs::write(without.path().join("trace.jsonl"), "old\n").unwrap();
    let (b, written) = run_into(without.path(), &s, None, &floor, None).unwrap();
    assert_eq!(written.len(), 4);
    assert!(!without.path().join("trace.jsonl").exists());
    assert_eq!(a.judged, b.judged);
    for name in [
        "summary.json",
        "trajectories.svg",
        "speed.svg",
        "distance.svg",
    ] {
        let x = std::fs::read(with.path().join(name)).unwrap();
        let y = std::fs::read(without.path().join(name)).unwrap();
        assert!(x == y, "{name} differs");
    }
    // The streamed trace equals the one kept in memory, byte for byte.
    let memory = run(&s, None, &floor).unwrap();
    let streamed = std::fs::read(with.path().join("trace.jsonl")).unwrap();
    assert!(streamed == memory.trace.unwrap());
    assert_eq!(a.records, 241);
    // No temporary file is left behind.
    let names: Vec<String> = std::fs::read_dir(with.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 5, "{names:?}");
}

/// 24 robots, three in each of the 8 rooms of a 4-rooms-per-side test building, each driving to
/// a room across the corridor, for `duration_s`: they crowd at the single-lane doors.
fn door_crowd(duration_s: f64) -> Scenario {
    let rooms = 4usize;
    let mut s = format!(
        "name = \"door-crowd\"\nduration_s = {duration_s:?}\n[building]\ndemo = {{ rooms_per_side = {rooms} }}\n"
    );
    let mut k = 0;
    for side in 0..2 {
        for i in 0..rooms {
            let x0 = i as f64 * 4.2;
            let y0 = if side == 0 { 0.0 } else { 6.8 };
            let heading = if side == 0 { 90.0 } else { -90.0 };
            for (dx, dy) in [(1.0, 1.0), (3.0, 1.0), (2.0, 2.8)] {
                k += 1;
                let room = side * rooms + i;
                let to = (room + rooms + k % 2) % (2 * rooms);
                s.push_str(&format!(
                    "[[robot]]\nname = \"R{k}\"\nstart = {{ x = {}, y = {}, heading_deg = {heading} }}\ncontroller = {{ kind = \"route\", to = \"Room {}\" }}\n",
                    x0 + dx,
                    y0 + dy,
                    to + 1
                ));
            }
        }
    }
    Scenario::from_toml(&s, "door-crowd.toml", Path::new(".")).unwrap()
}

/// The single-lane door check looks robots up in the step's grid instead of testing every
/// robot; a crowd at the doors decides as it does testing every robot (the events and distances
/// below are those of `door_wait_every_robot` in place of the grid lookup; the first 24 C-2
/// switches, to step 48, are those of commit 0376b34, before robots gave way).
#[test]
fn a_crowd_at_the_doors_decides_as_before_the_grid_lookup() {
    let s = door_crowd(5.0);
    let floor = prepare(&s, None).unwrap().floor().clone();
    let o = run(&s, None, &floor).unwrap();
    let c2: Vec<(u64, u32)> = o
        .events()
        .iter()
        .filter(|e| e.kind.tag() == "robot-role")
        .map(|e| (e.step, e.robot[1..].parse().unwrap()))
        .collect();
    let want = [
        (26, 3),
        (26, 9),
        (26, 12),
        (28, 1),
        (28, 2),
        (28, 7),
        (28, 8),
        (28, 10),
        (28, 11),
        (29, 6),
        (33, 4),
        (33, 5),
        (46, 15),
        (46, 18),
        (46, 21),
        (46, 24),
        (48, 13),
        (48, 14),
        (48, 16),
        (48, 17),
        (48, 19),
        (48, 20),
        (48, 22),
        (48, 23),
        (49, 1),
        (49, 4),
        (49, 7),
        (49, 10),
        (50, 2),
        (50, 5),
        (50, 8),
        (50, 11),
        (75, 5),
        (75, 13),
        (75, 14),
        (78, 22),
        (78, 23),
        (79, 19),
        (79, 20),
        (83, 16),
        (83, 17),
        (101, 1),
        (101, 7),
        (102, 10),
        (111, 2),
        (111, 8),
        (116, 11),
        (120, 4),
        (267, 13),
        (268, 1),
        (270, 22),
        (271, 10),
        (271, 19),
        (272, 7),
        (275, 16),
        (276, 4),
        (300, 1),
    ];
    assert_eq!(c2, want);
    let travelled: Vec<f64> = o
        .figures
        .iter()
        .map(|f| (f.travelled * 1e6).round() / 1e6)
        .collect();
    let want = [
        3.441189, 2.025437, 2.852854, 3.140181, 1.481141, 2.365717, 3.441189, 2.025437, 2.852854,
        3.407563, 2.0304, 2.894627, 2.716992, 1.512684, 4.465485, 2.570071, 1.513706, 4.736718,
        2.713715, 1.513283, 5.658664, 2.716922, 1.513152, 4.767318,
    ];
    assert_eq!(travelled, want);
}

/// The door crowd for 95 s. Before robots gave way, all 24 stopped within about 4 s and never
/// moved again (none arrived: robots leaving facing doors met nose to nose in the corridor, each
/// waiting for the other's door). Now the wait-for cycles and face-offs resolve and robots
/// merge into the corridor: 14 arrive, the last at 92.8 s, among them R6 and R18, the pair of
/// that first deadlock. (Not all: ten still jam at the corridor's dead end, as the README's simulation section says.)
#[test]
fn a_door_crowd_unjams_where_robots_met_nose_to_nose() {
    let s = door_crowd(95.0);
    let floor = prepare(&s, None).unwrap().floor().clone();
    let o = run(&s, None, &floor).unwrap();
    let arrived: Vec<(u32, f64)> = o
        .events()
        .iter()
        .filter(|e| e.kind.tag() == "arrived")
        .map(|e| (e.robot[1..].parse().unwrap(), e.t))
        .collect();
    let mut who: Vec<u32> = arrived.iter().map(|a| a.0).collect();
    who.sort_unstable();
    assert_eq!(
        who,
        [1, 2, 3, 4, 5, 6, 8, 10, 13, 14, 15, 16, 17, 18],
        "{arrived:?}"
    );
    // The first within 16 s, the last within 93 s.
    let first = arrived.iter().map(|a| a.1).fold(f64::INFINITY, f64::min);
    let last = arrived.iter().map(|a| a.1).fold(0.0, f64::max);
    assert!(first < 16.0 && last < 93.0, "{first} {last}");
    // R6 and R18 crossed the corridor both ways: each travelled more than the 6 m of its route.
    assert!(o.figures[5].travelled > 6.0 && o.figures[17].travelled > 6.0);
    // Giving way decides from the step's snapshot only: the first 20 s (robots give way from
    // the first seconds on) give the same bytes on one and four threads.
    let s = door_crowd(20.0);
    let traces: Vec<Vec<u8>> = [1, 4]
        .into_iter()
        .map(|threads| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build();
            let o = pool.unwrap().install(|| run(&s, None, &floor).unwrap());
            o.trace.unwrap()
        })
        .collect();
    assert!(traces[0] == traces[1], "traces differ");
}
