//! Scene JSON: parsing, defaults, validation messages, round trip.

use rccpack::scene::{scenes_from_json, Scene, SceneError};

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
    assert!(
        e.to_string().contains("object `far`") && e.to_string().contains("outside the space"),
        "{e}"
    );
}

#[test]
fn rejects_duplicate_id() {
    let e = err(r#"{"space":{"width":100,"height":100},"objects":[
        {"id":"x","class":"R","width":20,"height":20},{"id":"x","class":"G","width":20,"height":20}]}"#);
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
    assert!(
        e.to_string().contains("fixed object `w` has no position"),
        "{e}"
    );
    let e = err(
        r#"{"space":{"width":100,"height":100},"objects":[{"id":"z","class":"R","width":0,"height":20}]}"#,
    );
    assert!(e.to_string().contains("`z` has size 0x20"), "{e}");
    let e = err(r#"{"space":{"width":100,"height":100},"grid":0,"objects":[]}"#);
    assert_eq!(e.path(), "grid");
    let e = err(
        r#"{"space":{"width":100,"height":100},"objects":[{"id":"h","class":"R","x":3,"width":2,"height":2}]}"#,
    );
    assert_eq!(e.path(), "objects[0].y");
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
