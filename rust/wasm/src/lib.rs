//! planarkin-core for the web page, compiled to WebAssembly: what `rust/python` is for
//! Python. Convert and map errors; nothing numeric.
//!
//! The interface is a plain C ABI over the module's linear memory, so the page needs no
//! generated glue: the page writes a JSON request (UTF-8) into memory from [`pk_alloc`],
//! calls [`pk_call`], and reads the JSON reply at [`pk_out`] (its length is what
//! `pk_call` returned) and, for long arrays (paths, traces), the `f64` values at
//! [`pk_nums`] ([`pk_nums_len`] of them), which the reply indexes. A request is
//! `{"op": ..., ...}`; a refused one answers `{"error": message}` with the message that
//! Python's `ValueError` carries. Requests (see `request`):
//!
//! - `scene`: validate a scene (the file format) and keep it; the reply describes it;
//! - `pose`, `path`, `frame`: the kept scene solved at one input value, over the default
//!   361 values, or both (one animation frame); an input value is an angle (radians) or,
//!   for a scene driven by a slot or prismatic pair, the displacement from the drawn pose
//!   (scene units), and the default values span one turn or that input's stroke;
//! - `assemblies`, `circuits`: every assembly at an input value, and their circuits;
//! - `forces`: a scene with loads: the statics input effort and every pin reaction over
//!   the default 361 input values (the core's `forces`, as `Scene.statics()`);
//! - `fourbar`: a four-bar by its lengths: pose, coupler path, Grashof and Barker class,
//!   limit positions;
//! - `atlas_shard`, `atlas_describe`, `atlas_match`, `atlas_pose`: the path atlas (the
//!   core's `atlas`, for the page's "draw a path" mode): a shard of entries (its columns
//!   in the numbers), a curve's descriptor, candidates placed onto a target, an entry's
//!   pose.
//!
//! Inside, laid out as the core and the Python bindings are: `fourbar`, `atlas` and the
//! `scene/` folder (`format`, `sweep`, `branches`) convert one subject each; `json` holds
//! the shared conversions (status names, numbers).

mod atlas;
mod fourbar;
mod json;
mod scene;

use std::cell::RefCell;

use serde_json::{json, Value};

/// What the module keeps between calls: the current scene and the last reply.
#[derive(Default)]
struct State {
    scene: Option<scene::Kept>,
    out: Vec<u8>,
    nums: Vec<f64>,
}

thread_local! {
    static STATE: RefCell<State> = RefCell::new(State::default());
}

/// Allocates `len` bytes for a request; the page frees them with [`pk_free`].
#[no_mangle]
pub extern "C" fn pk_alloc(len: usize) -> *mut u8 {
    let mut v = Vec::<u8>::with_capacity(len.max(1));
    let p = v.as_mut_ptr();
    std::mem::forget(v);
    p
}

/// Frees what [`pk_alloc`] gave.
///
/// # Safety
/// `ptr` and `len` must be exactly what one call of [`pk_alloc`] got and returned.
#[no_mangle]
pub unsafe extern "C" fn pk_free(ptr: *mut u8, len: usize) {
    drop(Vec::from_raw_parts(ptr, 0, len.max(1)));
}

/// Answers the JSON request of `len` bytes at `ptr`; returns the reply's length in bytes
/// (the reply is at [`pk_out`]).
///
/// # Safety
/// `ptr` must point to `len` readable bytes.
#[no_mangle]
pub unsafe extern "C" fn pk_call(ptr: *const u8, len: usize) -> usize {
    let bytes = std::slice::from_raw_parts(ptr, len);
    STATE.with(|s| {
        let mut s = s.borrow_mut();
        s.nums.clear();
        let reply = match std::str::from_utf8(bytes) {
            Ok(text) => request(&mut s, text),
            Err(e) => Err(format!("request is not UTF-8: {e}")),
        };
        let reply = reply.unwrap_or_else(|message| json!({ "error": message }));
        s.out = serde_json::to_vec(&reply).expect("a Value always serialises");
        s.out.len()
    })
}

/// The last reply (UTF-8 JSON).
#[no_mangle]
pub extern "C" fn pk_out() -> *const u8 {
    STATE.with(|s| s.borrow().out.as_ptr())
}

/// The last reply's numbers (the arrays it indexes).
#[no_mangle]
pub extern "C" fn pk_nums() -> *const f64 {
    STATE.with(|s| s.borrow().nums.as_ptr())
}

/// How many numbers [`pk_nums`] holds.
#[no_mangle]
pub extern "C" fn pk_nums_len() -> usize {
    STATE.with(|s| s.borrow().nums.len())
}

/// One request: `{"op": ..., ...}`.
fn request(s: &mut State, text: &str) -> Result<Value, String> {
    let req: Value = serde_json::from_str(text).map_err(|e| format!("request is not JSON: {e}"))?;
    let op = req.get("op").and_then(Value::as_str).ok_or("request has no \"op\"")?;
    let State { scene: kept, nums, .. } = s;
    match op {
        "scene" => {
            let sc = scene::Kept::new(req.get("scene").ok_or("request has no \"scene\"")?)?;
            let info = sc.describe();
            *kept = Some(sc);
            Ok(info)
        }
        "fourbar" => fourbar::solve(&req, nums),
        "atlas_shard" => atlas::shard(&req, nums),
        "atlas_describe" => atlas::descriptor(&req),
        "atlas_match" => atlas::placements(&req),
        "atlas_pose" => atlas::entry_pose(&req),
        "pose" | "path" | "frame" | "assemblies" | "circuits" | "forces" => {
            let sc = kept.as_ref().ok_or("no scene: send a \"scene\" request first")?;
            match op {
                "pose" => sc.pose(json::number(&req, "theta")?),
                "path" => sc.path(nums),
                "frame" => {
                    let pose = sc.pose(json::number(&req, "theta")?)?;
                    Ok(json!({ "pose": pose, "path": sc.path(nums)? }))
                }
                "assemblies" => sc.assemblies(json::number(&req, "theta")?),
                "forces" => sc.forces(nums),
                _ => sc.circuits(json::number(&req, "theta")?, nums),
            }
        }
        other => Err(format!("unknown op {other:?}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FOURBAR: &str = r#"{"points": {"O2": [0, 0], "O4": [6, 0], "A": [2, 0], "B": [4.0, 4.58257569495584]},
        "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]},
        "ground": "ground", "input": {"link": "crank", "pivot": "O2"}}"#;

    fn ask(s: &mut State, req: &str) -> Value {
        request(s, req).unwrap_or_else(|e| json!({ "error": e }))
    }

    #[test]
    fn the_c_interface_round_trips_a_request() {
        let req = br#"{"op": "nope"}"#;
        let p = pk_alloc(req.len());
        let reply = unsafe {
            std::ptr::copy_nonoverlapping(req.as_ptr(), p, req.len());
            let n = pk_call(p, req.len());
            pk_free(p, req.len());
            std::slice::from_raw_parts(pk_out(), n).to_vec()
        };
        assert_eq!(String::from_utf8(reply).unwrap(), r#"{"error":"unknown op \"nope\""}"#);
        assert_eq!(pk_nums_len(), 0);
    }

    #[test]
    fn a_scene_is_kept_and_solved() {
        let mut s = State::default();
        assert_eq!(ask(&mut s, r#"{"op": "pose", "theta": 0}"#)["error"], "no scene: send a \"scene\" request first");
        let info = ask(&mut s, &format!(r#"{{"op": "scene", "scene": {FOURBAR}}}"#));
        assert_eq!(info["names"], json!(["O2", "O4", "A", "B"]));
        assert_eq!(info["input_angle"], 0.0);
        let pose = ask(&mut s, r#"{"op": "pose", "theta": 0}"#);
        assert_eq!(pose["status"], "CONVERGED");
        let b = pose["points"][3].as_array().unwrap();
        assert!((b[0].as_f64().unwrap() - 4.0).abs() < 1e-12 && (b[1].as_f64().unwrap() - 21f64.sqrt()).abs() < 1e-12);
        let path = ask(&mut s, r#"{"op": "path"}"#);
        assert_eq!((path["n"].as_u64(), path["offset"].as_u64()), (Some(361), Some(0)));
        assert_eq!(s.nums.len(), 361 * 4 * 2);
    }

    #[test]
    fn bad_scenes_name_the_entry_as_python_does() {
        let mut s = State::default();
        let cases = [
            (r#"[1]"#, "scene: must be a mapping, got list"),
            (r#"{"points": {}, "links": {}, "ground": "g"}"#, "input: is required"),
            (
                r#"{"points": {"A": [1]}, "links": {}, "ground": "g", "input": {}}"#,
                "points.A: must be a pair [x, y], got [1]",
            ),
            (
                r#"{"points": {"A": [1, "x"]}, "links": {}, "ground": "g", "input": {}}"#,
                "points.A[1] must be a real number, got 'x'",
            ),
            (
                r#"{"colour": 1.5}"#,
                "scene: unknown keys ['colour']; known keys: name, description, units, points, links, ground, input, \
                 output, outputs, slots, prismatic, lengths, loads, limits",
            ),
            (
                r#"{"points": {"A": [0, 0]}, "links": {"l": ["A", 2]}, "ground": "l", "input": {"link": "l", "pivot": "A"}}"#,
                "links.l: must be a list of point names, got ['A', 2]",
            ),
        ];
        for (scene, message) in cases {
            let reply = ask(&mut s, &format!(r#"{{"op": "scene", "scene": {scene}}}"#));
            assert_eq!(reply["error"], message, "{scene}");
        }
        // past the structural checks, the core's own validation and words
        let bad = FOURBAR.replace(r#""rocker": ["O4", "B"]"#, r#""rocker": ["O4", "Q"]"#);
        let reply = ask(&mut s, &format!(r#"{{"op": "scene", "scene": {bad}}}"#));
        assert_eq!(reply["error"], "links.rocker: unknown point \"Q\"");
    }

    /// The elliptic trammel: A slides along x (the input), B along y; P on the bar.
    const TRAMMEL: &str = r#"{"points": {"O": [0, 0], "X": [1, 0], "Y": [0, 1], "A": [60, 0], "B": [0, 80], "P": [36, 32]},
        "links": {"ground": ["O", "X", "Y"], "bar": ["A", "B", "P"]}, "ground": "ground",
        "input": {"slot": "a"}, "outputs": ["P"],
        "slots": {"a": {"point": "A", "guide": "ground", "line": ["O", "X"]},
                  "b": {"point": "B", "guide": "ground", "line": ["O", "Y"]}}}"#;

    #[test]
    fn a_linear_input_sweeps_its_stroke() {
        let mut s = State::default();
        let info = ask(&mut s, &format!(r#"{{"op": "scene", "scene": {TRAMMEL}}}"#));
        assert_eq!(info["input_kind"], "displacement");
        assert_eq!(info["input"], Value::Null);
        assert_eq!(info["linear_input"], json!({"kind": "slot", "name": "a", "index": 0, "guide": 0}));
        assert_eq!(info["slots"][1], json!({"name": "b", "point": 4, "guide": 0, "line": [0, 2]}));
        assert_eq!(info["size"], 80.0);
        // A reaches x = -100 and x = 100 (B on the x axis): s from -160 to 40
        let stroke: Vec<f64> = info["stroke"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        assert!((stroke[0] + 160.0).abs() < 1e-6 && (stroke[1] - 40.0).abs() < 1e-6, "{stroke:?}");
        let path = ask(&mut s, r#"{"op": "path"}"#);
        assert_eq!(path["theta"][0].as_f64(), Some(stroke[0]));
        assert_eq!(path["theta"][360].as_f64(), Some(stroke[1]));
        // the displacement from the drawn pose, in scene units
        let pose = ask(&mut s, r#"{"op": "pose", "theta": -30}"#);
        assert_eq!(pose["status"], "CONVERGED");
        let (a, b) = (&pose["points"][3], &pose["points"][4]);
        assert!((a[0].as_f64().unwrap() - 30.0).abs() < 1e-12 && a[1].as_f64().unwrap().abs() < 1e-12);
        assert!((b[1].as_f64().unwrap() - (100f64.powi(2) - 900.0).sqrt()).abs() < 1e-12);
    }

    #[test]
    fn a_linear_output_is_read_from_the_core() {
        let mut s = State::default();
        let scene = TRAMMEL.replace(r#""outputs": ["P"],"#, r#""output": {"slot": "b"},"#);
        let info = ask(&mut s, &format!(r#"{{"op": "scene", "scene": {scene}}}"#));
        assert_eq!(info["linear_output"], json!({"kind": "slot", "name": "b"}));
        let pose = ask(&mut s, r#"{"op": "pose", "theta": -30}"#);
        // B along O -> Y from its drawn 80: A at x = 30 puts it at y = sqrt(100^2 - 30^2)
        let b = (100f64.powi(2) - 900.0).sqrt() - 80.0;
        assert!((pose["output"].as_f64().unwrap() - b).abs() < 1e-12, "{}", pose["output"]);
        let path = ask(&mut s, r#"{"op": "path"}"#);
        assert_eq!(path["output"].as_array().map(Vec::len), Some(361));
        let angle = ask(&mut s, &format!(r#"{{"op": "scene", "scene": {FOURBAR}}}"#));
        assert_eq!(angle["linear_output"], Value::Null);
        assert_eq!(ask(&mut s, r#"{"op": "path"}"#)["output"], Value::Null);
    }

    #[test]
    fn bad_slots_name_the_entry_as_python_does() {
        let mut s = State::default();
        let cases = [
            (r#""slots": [1]"#, "slots: must be a table name -> {point, guide, line}"),
            (
                r#""slots": {"c": {"point": "A"}}"#,
                "slots.c: must be a table with keys 'point', 'guide' and 'line', got {'point': 'A'}",
            ),
            (
                r#""slots": {"a": {"point": "A", "guide": "ground", "line": ["O", 3]}}"#,
                "slots.a.line: must be a pair of point names, got ['O', 3]",
            ),
            (
                r#""slots": {"a": {"point": "A", "guide": 1, "line": ["O", "X"]}}"#,
                "slots.a.guide: must be a name, got 1",
            ),
            (r#""input": {"slot": 3}"#, "input.slot: must be a slot name, got 3"),
            (r#""input": {"slot": "zz"}"#, "input.slot: \"zz\" is not a slot"),
            (r#""output": {"slot": "zz"}"#, "output.slot: 'zz' is not a slot"),
            (r#""output": {"prismatic": "a"}"#, "output.prismatic: 'a' is not a prismatic"),
            (
                r#""input": {"link": "bar"}"#,
                "input: must be a table with keys 'link' and 'pivot' (an angle), or with one key 'slot' or \
                 'prismatic' (a displacement), got {'link': 'bar'}",
            ),
            (
                r#""prismatic": {"p": null}"#,
                "prismatic.p: must be a table with keys 'link', 'guide' and 'line', got None",
            ),
            (r#""slots": null"#, "input.slot: \"a\" is not a slot"),
        ];
        for (change, message) in cases {
            // a later key replaces an earlier one (serde_json keeps the last)
            let scene = format!("{}, {change}}}", TRAMMEL.trim_end().strip_suffix('}').unwrap());
            let reply = ask(&mut s, &format!(r#"{{"op": "scene", "scene": {scene}}}"#));
            assert_eq!(reply["error"], message, "{change}");
        }
    }

    #[test]
    fn the_fourbar_reports_its_class_and_limits() {
        let mut s = State::default();
        let r =
            ask(&mut s, r#"{"op": "fourbar", "r": [4, 3, 2, 1.5], "theta2": 2.0, "mode": "open", "p": 1, "delta": 0}"#);
        assert_eq!(r["status"], "NOT_ASSEMBLABLE");
        assert_eq!(r["grashof"]["barker"], "RRR1");
        // Python's names: Grashof.condition, FourBar.transmission_angle
        assert_eq!(r["grashof"]["condition"], "non-grashof");
        assert!(r.get("transmission_angle").is_some() && r.get("transmission").is_none());
        assert!(r["grashof"].get("class").is_none());
        let ok = ask(&mut s, r#"{"op": "fourbar", "r": [6, 2, 5, 5], "theta2": 0.5, "p": 1, "delta": 0}"#);
        assert_eq!((&ok["status"], &ok["grashof"]["condition"]), (&"CONVERGED".into(), &"grashof".into()));
        assert!(ok["transmission_angle"].as_f64().is_some_and(|m| m > 0.0 && m <= std::f64::consts::FRAC_PI_2));
        assert_eq!(r["limits"]["full_rotation"], false);
        assert_eq!(r["limits"]["dead_points"].as_array().unwrap().len(), 2);
        let bad = ask(&mut s, r#"{"op": "fourbar", "r": [4, 3, -2, 1.5], "theta2": 0, "p": 1, "delta": 0}"#);
        assert_eq!(bad["error"], "r3 must be finite and > 0, got -2.0");
    }

    /// A rhombus four-bar (every link 1) at a right crank angle: A (0, 1), B (1, 1) on the
    /// left of A -> O4, P half along A-B and half its length across, by hand.
    #[test]
    fn an_atlas_entrys_pose_by_hand() {
        let mut s = State::default();
        let r = ask(
            &mut s,
            &format!(
                r#"{{"op": "atlas_pose", "params": [1, 1, 1, 0.5, 0.5], "signs": [1], "theta": {}}}"#,
                std::f64::consts::FRAC_PI_2
            ),
        );
        assert_eq!(r["names"], json!(["O2", "O4", "A", "B", "P"]));
        let want = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0], [0.5, 1.5]];
        for (k, w) in want.iter().enumerate() {
            for c in 0..2 {
                assert!((r["points"][k][c].as_f64().unwrap() - w[c]).abs() < 1e-12, "{k} {r}");
            }
        }
        // |A - O4| = 3 > r3 + r4: no assembly
        let none =
            ask(&mut s, r#"{"op": "atlas_pose", "params": [2, 1, 1, 0.5, 0.5], "signs": [1], "theta": 3.14159}"#);
        assert_eq!(none["points"], Value::Null);
        let bad = ask(&mut s, r#"{"op": "atlas_pose", "params": [1, 1, 1], "signs": [1], "theta": 0}"#);
        assert_eq!(bad["error"], "params has length 3, expected 5");
        let bad = ask(&mut s, r#"{"op": "atlas_shard", "topology": "five-bar", "seed": 0, "start": 0, "count": 1}"#);
        assert!(bad["error"].as_str().unwrap().starts_with("topology"), "{bad}");
    }

    /// A crank-rocker's coupler curve (circle intersections written here), turned a
    /// quarter, doubled and shifted: the placement finds that similarity and the input
    /// angle of the first point (to the placement's grid: 128 samples of the curve, 256
    /// starts, so about 1% of the size).
    #[test]
    fn an_atlas_placement_finds_the_similarity() {
        let (r2, r3, r4, u, v) = (0.3, 1.0, 0.8, 0.5, 0.3);
        let coupler = |t: f64| {
            let a = [r2 * t.cos(), r2 * t.sin()];
            let (dx, dy) = (1.0 - a[0], -a[1]);
            let d = dx.hypot(dy);
            let along = (r3 * r3 - r4 * r4 + d * d) / (2.0 * d);
            let h = (r3 * r3 - along * along).sqrt();
            let b = [a[0] + (along * dx - h * dy) / d, a[1] + (along * dy + h * dx) / d];
            let (bx, by) = (b[0] - a[0], b[1] - a[1]);
            [a[0] + u * bx - v * by, a[1] + u * by + v * bx]
        };
        let t0 = 0.4;
        let target: Vec<[f64; 2]> = (0..60)
            .map(|k| coupler(t0 + std::f64::consts::TAU * k as f64 / 60.0))
            .map(|[x, y]| [3.0 - 2.0 * y, 1.0 + 2.0 * x])
            .collect();
        let mut s = State::default();
        let req = json!({"op": "atlas_match", "params": [r2, r3, r4, u, v], "signs": [1], "target": target,
                         "closed": true, "offsets": 16});
        let r = ask(&mut s, &req.to_string());
        let p = &r["placements"][0];
        let got = |v: &Value, k: usize| v[k].as_f64().unwrap();
        assert!(p["cost"].as_f64().unwrap() < 1e-4, "{p}");
        assert!(got(&p["a"], 0).abs() < 0.03 && (got(&p["a"], 1) - 2.0).abs() < 0.03, "{p}");
        assert!((got(&p["b"], 0) - 3.0).abs() < 0.03 && (got(&p["b"], 1) - 1.0).abs() < 0.03, "{p}");
        assert_eq!(p["reversed"], false);
        let th = got(&p["theta"], 0);
        assert!(
            ((th - t0 + 3.0 * std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI).abs()
                < 2e-2,
            "{th}"
        );
        let desc = ask(&mut s, r#"{"op": "atlas_describe", "points": [[1, 1], [1, "x"]], "closed": true}"#);
        assert_eq!(desc["error"], "points must be a list of [x, y] pairs of real numbers");
        let desc = ask(&mut s, r#"{"op": "atlas_describe", "points": [[0, 0], [1, 0], [0, 1]], "closed": true}"#);
        assert_eq!(desc["descriptor"].as_array().map(Vec::len), Some(32));
        let shard = ask(&mut s, r#"{"op": "atlas_shard", "seed": 0, "start": 5, "count": 3}"#);
        assert_eq!(shard["descriptor"], json!({"offset": 3 * 8, "cols": 32}));
        assert_eq!(s.nums.len(), 3 * (5 + 1 + 1 + 1 + 32));
    }

    /// A pendulum under gravity: the torque that holds it is m g (l cos t) at every angle,
    /// by hand; a scene without loads has none.
    #[test]
    fn forces_of_a_loaded_scene() {
        let mut s = State::default();
        let arm = r#"{"points": {"O": [0, 0], "X": [1, 0], "G": [0.4, 0.3]},
            "links": {"ground": ["O", "X"], "arm": ["O", "G"]}, "ground": "ground",
            "input": {"link": "arm", "pivot": "O"}, "units": {"length": "m"},
            "loads": {"gravity": [0, -9.81], "masses": {"arm": {"mass": 2.0, "center": "G", "inertia": 0.1}}}}"#;
        let info = ask(&mut s, &format!(r#"{{"op": "scene", "scene": {arm}}}"#));
        assert_eq!(info["loads"], true);
        let f = ask(&mut s, r#"{"op": "forces"}"#);
        assert_eq!(f["error"], Value::Null);
        assert_eq!((f["n"].as_u64(), f["unit"].as_str()), (Some(361), Some("N*m")));
        let at = f["effort"].as_u64().unwrap() as usize;
        for (i, t) in f["theta"].as_array().unwrap().iter().enumerate() {
            let want = 2.0 * 9.81 * 0.5 * t.as_f64().unwrap().cos();
            assert!((s.nums[at + i] - want).abs() < 1e-12, "{i}");
        }
        assert_eq!(f["pins"], json!([{"point": 0, "link": 1, "offset": at + 361}]));
        ask(&mut s, &format!(r#"{{"op": "scene", "scene": {FOURBAR}}}"#));
        assert_eq!(ask(&mut s, r#"{"op": "forces"}"#), json!({"loads": false}));
    }
}
