//! Scene JSON: parsing, defaults, validation messages, round trip.

use rccpack::scene::{scenes_from_json, Scene, SceneError, SceneErrorKind};

fn err(text: &str) -> SceneError {
    Scene::from_json(text).expect_err("scene should be rejected")
}

const OK: &str = r#"{
  "space": {"x": 0, "y": 0, "width": 100, "height": 100},
  "grid": 10,
  "objects": [
    {"id": "wall", "class": "W", "x": 0, "y": 0, "width": 100, "height": 10, "fixed": true},
    {"id": "r1", "class": "R", "x": 10, "y": 10, "width": 20, "height": 20},
    {"class": "R", "width": 20, "height": 20}
  ]
}"#;

#[test]
fn parses_with_defaults() {
    let s = Scene::from_json(OK).unwrap();
    assert_eq!(s.objects.len(), 3);
    assert_eq!(s.objects[2].id, "R2", "default id is <class><index>");
    assert!(!s.objects[1].fixed);
    assert!(!s.objects[2].is_placed());
    let s2 = Scene::from_json(r#"{"space":{"width":5,"height":5},"objects":[]}"#).unwrap();
    assert_eq!((s2.space.x, s2.space.y, s2.grid), (0, 0, 10));
}

#[test]
fn round_trip_load_save_load() {
    let s = Scene::from_json(OK).unwrap();
    let again = Scene::from_json(&s.to_json()).unwrap();
    assert_eq!(s, again);
    let many = scenes_from_json(&rccpack::scene::scenes_to_json(&[s.clone(), s.clone()])).unwrap();
    assert_eq!(many, vec![s.clone(), s]);
}

#[test]
fn rejects_float_naming_the_field() {
    let e = err(
        r#"{"space":{"width":100,"height":100},"objects":[{"class":"R","x":12.5,"y":0,"width":1,"height":1}]}"#,
    );
    assert_eq!(e.path(), "objects[0].x");
    assert!(e.to_string().contains("12.5"), "{e}");
    let e = err(
        r#"{"space":{"width":100,"height":100},"objects":[{"class":"R","x":2.0,"y":0,"width":1,"height":1}]}"#,
    );
    assert_eq!(e.path(), "objects[0].x", "2.0 is not an integer either");
}

#[test]
fn rejects_unknown_field() {
    let e = err(
        r#"{"space":{"width":100,"height":100},"objects":[{"class":"R","colour":"red","width":1,"height":1}]}"#,
    );
    assert!(e.to_string().contains("unknown field `colour`"), "{e}");
    assert!(e.path().starts_with("objects[0]"), "{}", e.path());
}

#[test]
fn rejects_overlap_naming_both_objects() {
    let e = err(r#"{"space":{"width":100,"height":100},"objects":[
        {"id":"a","class":"R","x":0,"y":0,"width":20,"height":20},
        {"id":"b","class":"R","x":10,"y":10,"width":20,"height":20}]}"#);
    assert_eq!(e.kind(), SceneErrorKind::Overlap);
    assert_eq!(
        e.to_string(),
        "objects[1]: objects `a` (objects[0]) and `b` (objects[1]) overlap"
    );
}

#[test]
fn touching_is_not_overlap() {
    Scene::from_json(
        r#"{"space":{"width":100,"height":100},"objects":[
        {"id":"a","class":"R","x":0,"y":0,"width":20,"height":20},
        {"id":"b","class":"R","x":20,"y":20,"width":20,"height":20},
        {"id":"c","class":"R","x":20,"y":0,"width":20,"height":20}]}"#,
    )
    .unwrap();
}

#[test]
fn rejects_out_of_space() {
    let e = err(
        r#"{"space":{"width":100,"height":100},"objects":[{"id":"far","class":"R","x":90,"y":0,"width":20,"height":20}]}"#,
    );
    assert_eq!(e.kind(), SceneErrorKind::Outside);
    assert!(e.to_string().contains("object `far`"), "{e}");
}

#[test]
fn rejects_duplicate_id() {
    let e = err(r#"{"space":{"width":100,"height":100},"objects":[
        {"id":"x","class":"R","width":20,"height":20},{"id":"x","class":"G","width":20,"height":20}]}"#);
    assert_eq!(e.kind(), SceneErrorKind::DuplicateId);
    assert_eq!(
        e.to_string(),
        "objects[1].id: duplicate object id `x` (also objects[0])"
    );
}

#[test]
fn rejects_fixed_without_position_and_bad_sizes() {
    let e = err(
        r#"{"space":{"width":100,"height":100},"objects":[{"id":"w","class":"W","width":20,"height":20,"fixed":true}]}"#,
    );
    assert_eq!(
        (e.kind(), e.path()),
        (SceneErrorKind::FixedUnplaced, "objects[0]")
    );
    let e = err(
        r#"{"space":{"width":100,"height":100},"objects":[{"id":"z","class":"R","width":0,"height":20}]}"#,
    );
    assert_eq!(e.kind(), SceneErrorKind::BadSize);
    assert!(e.to_string().contains("`z` has size 0x20"), "{e}");
    let e = err(r#"{"space":{"width":100,"height":100},"grid":0,"objects":[]}"#);
    assert_eq!((e.kind(), e.path()), (SceneErrorKind::BadGrid, "grid"));
    let e = err(
        r#"{"space":{"width":100,"height":100},"objects":[{"id":"h","class":"R","x":3,"width":2,"height":2}]}"#,
    );
    assert_eq!(
        (e.kind(), e.path()),
        (SceneErrorKind::HalfPlaced, "objects[0].y")
    );
}

#[test]
fn demonstrations_errors_carry_the_scene_index() {
    let one = r#"{"space":{"width":100,"height":100},"objects":[]}"#;
    let bad = r#"{"space":{"width":100,"height":100},"objects":[{"class":"R","x":1.5,"y":0,"width":1,"height":1}]}"#;
    let e = scenes_from_json(&format!("[{one},{bad}]")).unwrap_err();
    assert_eq!(e.path(), "[1].objects[0].x");
    let e = scenes_from_json("[1, 2").unwrap_err();
    assert!(e.to_string().contains("line 1"), "{e}");
}

#[test]
fn on_grid_is_relative_to_the_space_origin() {
    let s = Scene::from_json(
        r#"{"space":{"x":5,"y":-5,"width":100,"height":100},"objects":[
        {"id":"a","class":"R","x":15,"y":5,"width":10,"height":10},
        {"id":"b","class":"R","x":40,"y":5,"width":10,"height":10}]}"#,
    )
    .unwrap();
    assert!(s.on_grid(&s.objects[0]));
    assert!(!s.on_grid(&s.objects[1]));
}

/// Coordinates far out of range get a field-named error (no
/// overflow in `space.x + width`, no wrapping `abs()`), and the documented
/// bound itself is accepted.
#[test]
fn coordinates_at_and_past_the_documented_bound() {
    use rccpack::limits::MAX_SCENE_COORD;
    let scene =
        |space: &str, obj: &str| format!(r#"{{"space":{space},"grid":1,"objects":[{obj}]}}"#);
    // At the bound: accepted.
    let at = scene(
        &format!(
            r#"{{"x":{},"y":{},"width":{MAX_SCENE_COORD},"height":{MAX_SCENE_COORD}}}"#,
            -MAX_SCENE_COORD, -MAX_SCENE_COORD
        ),
        &format!(
            r#"{{"class":"R","x":{},"y":-1,"width":{MAX_SCENE_COORD},"height":1}}"#,
            -MAX_SCENE_COORD
        ),
    );
    Scene::from_json(&at).expect("the bound itself is accepted");
    // The space's corner plus its size reaches 2·MAX_SCENE_COORD; still fine.
    let far = scene(
        &format!(
            r#"{{"x":{MAX_SCENE_COORD},"y":{MAX_SCENE_COORD},"width":{MAX_SCENE_COORD},"height":{MAX_SCENE_COORD}}}"#
        ),
        &format!(
            r#"{{"class":"R","x":{},"y":{MAX_SCENE_COORD},"width":{MAX_SCENE_COORD},"height":1}}"#,
            MAX_SCENE_COORD
        ),
    );
    Scene::from_json(&far).expect("edges up to 2·MAX_SCENE_COORD are fine");
    let cases: Vec<(String, &str)> = vec![
        (
            scene(r#"{"x":9223372036854775807,"width":10,"height":10}"#, ""),
            "space.x",
        ),
        (
            scene(
                &format!(r#"{{"x":{},"width":10,"height":10}}"#, MAX_SCENE_COORD + 1),
                "",
            ),
            "space.x",
        ),
        (
            scene(r#"{"y":-9223372036854775808,"width":10,"height":10}"#, ""),
            "space.y",
        ),
        (
            scene(r#"{"width":9223372036854775807,"height":10}"#, ""),
            "space.width",
        ),
        (
            scene(
                &format!(r#"{{"width":10,"height":{}}}"#, MAX_SCENE_COORD + 1),
                "",
            ),
            "space.height",
        ),
        (
            scene(
                r#"{"width":10,"height":10}"#,
                r#"{"class":"R","x":-9223372036854775808,"y":0,"width":1,"height":1}"#,
            ),
            "objects[0].x",
        ),
        (
            scene(
                r#"{"width":10,"height":10}"#,
                r#"{"class":"R","x":0,"y":9223372036854775807,"width":1,"height":1}"#,
            ),
            "objects[0].y",
        ),
        (
            scene(
                r#"{"width":10,"height":10}"#,
                r#"{"class":"R","x":0,"y":0,"width":9223372036854775807,"height":1}"#,
            ),
            "objects[0].width",
        ),
        (
            scene(
                r#"{"width":10,"height":10}"#,
                r#"{"class":"R","width":1,"height":1000000000000001}"#,
            ),
            "objects[0].height",
        ),
    ];
    for (text, path) in cases {
        let e = err(&text);
        assert_eq!(e.path(), path, "{text}: {e}");
        let m = e.to_string();
        assert!(
            m.contains("out of range") || m.contains("too large"),
            "{text}: {m}"
        );
        assert!(m.contains("1000000000000000"), "names the limit: {m}");
    }
    let e = err(r#"{"space":{"width":10,"height":10},"grid":9223372036854775807,"objects":[]}"#);
    assert_eq!(e.path(), "grid");
}

/// `on_grid` never divides by zero or overflows on a scene built in code.
#[test]
fn on_grid_is_total() {
    let mut s = Scene::from_json(OK).unwrap();
    let o = s.objects[1].clone();
    assert!(s.on_grid(&o));
    s.grid = 0;
    assert!(!s.on_grid(&o));
    s.grid = 3;
    s.space.x = i64::MIN;
    let mut far = o.clone();
    far.x = Some(i64::MAX);
    let _ = s.on_grid(&far);
}
