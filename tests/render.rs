//! Pictures: SVG structure, PNG bytes, violation outlines, file extensions.
//!
//! Set `RCCPACK_RENDER_OUT=/some/dir` to also write the example pictures
//! there for a look.

use rccpack::relations::{Contact, Dir, Kind, Relation};
use rccpack::render::{render_png, render_svg, render_to_path, RenderError, RenderOptions};
use rccpack::rules::{Atom, Formula, Rule, RuleSet, Strength, Target};
use rccpack::scene::{scenes_from_json, Scene};
use std::path::PathBuf;

fn scene() -> Scene {
    Scene::from_json(
        r#"{"space":{"width":200,"height":120},"grid":10,"objects":[
          {"id":"wall","class":"W","x":0,"y":0,"width":200,"height":20,"fixed":true},
          {"id":"r1","class":"R","x":20,"y":20,"width":40,"height":40},
          {"id":"b1","class":"B","x":100,"y":20,"width":40,"height":40},
          {"id":"g<1>","class":"G","x":150,"y":70,"width":40,"height":40},
          {"id":"q1","class":"Q","width":40,"height":30}]}"#,
    )
    .unwrap()
}

/// `DR_N(B, R)`: b1 sits level with r1, so it is the only violator.
fn rules() -> RuleSet {
    let atom = |k, d, s: &str, t: &str| {
        Formula::Atom(Atom::new(Relation::new(k, d), s, Target::Class(t.into())))
    };
    RuleSet::new(vec![
        Rule::new("blue_north_of_red", atom(Kind::DR, Dir::N, "B", "R")),
        Rule::new("green_east_of_red", atom(Kind::DR, Dir::E, "G", "R"))
            .with_strength(Strength::Hard),
    ])
}

fn out_dir() -> Option<PathBuf> {
    std::env::var_os("RCCPACK_RENDER_OUT").map(PathBuf::from)
}

#[test]
fn svg_has_one_rect_per_object_and_labels() {
    let s = scene();
    let svg = render_svg(&s, None, &RenderOptions::default());
    assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
    assert_eq!(svg.matches("class=\"obj\"").count(), s.objects.len());
    for id in ["r1", "b1", "g&lt;1&gt;", "q1"] {
        assert!(svg.contains(&format!(">{id}</text>")), "label {id} missing");
    }
    assert!(!svg.contains("g<1>"), "ids must be escaped");
    assert!(svg.contains("N ↑"));
    assert!(svg.contains("unplaced (1)"));
    assert!(svg.contains("#d9534f") && svg.contains("#5cb85c") && svg.contains("#428bca"));
    assert!(svg.contains("class=\"grid\""));
    assert!(!svg.contains("violator"));
    // The SVG must be well-formed enough for resvg.
    render_png(&s, None, &RenderOptions::default()).unwrap();
}

#[test]
fn north_is_up() {
    let s = scene();
    let svg = render_svg(&s, None, &RenderOptions::default());
    let y_of = |id: &str| -> f64 {
        let g = svg.find(&format!("data-id=\"{id}\"")).unwrap();
        let rest = &svg[g..];
        let y = rest.find(" y=\"").unwrap() + 4;
        rest[y..y + rest[y..].find('"').unwrap()].parse().unwrap()
    };
    // g<1> (y = 70) is north of r1 (y = 20): higher up on screen.
    assert!(y_of("g&lt;1&gt;") < y_of("r1"));
    assert!(y_of("r1") < y_of("wall"));
}

#[test]
fn png_has_signature_and_expected_size() {
    let s = scene();
    for scale in [1.0, 2.5] {
        let opts = RenderOptions {
            scale,
            title: Some("demo <1>".into()),
            ..RenderOptions::default()
        };
        let svg = render_svg(&s, Some(&rules()), &opts);
        let png = render_png(&s, Some(&rules()), &opts).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        let attr = |name: &str| -> u32 {
            let i = svg.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
            svg[i..i + svg[i..].find('"').unwrap()].parse().unwrap()
        };
        let decoded = resvg::tiny_skia::Pixmap::decode_png(&png).unwrap();
        assert_eq!(
            (decoded.width(), decoded.height()),
            (attr("width"), attr("height"))
        );
        // The table is 200 units wide: the picture is wider than that.
        assert!(decoded.width() as f64 > 200.0 * scale);
    }
}

#[test]
fn png_draws_text() {
    // The same scene with and without a title differs in pixels only if
    // fonts are loaded (resvg silently drops text otherwise).
    let s = scene();
    let plain = render_png(&s, None, &RenderOptions::default()).unwrap();
    let titled = render_png(
        &s,
        None,
        &RenderOptions {
            title: Some("TITLE".into()),
            ..RenderOptions::default()
        },
    )
    .unwrap();
    assert_ne!(plain, titled);
}

#[test]
fn violators_are_outlined_once() {
    let s = scene();
    let r = rules();
    let ev = rccpack::eval::evaluate(&s, &r, Contact::Point);
    assert_eq!(ev.rules[0].violators, ["b1"]);
    assert!(ev.rules[1].violators.is_empty());
    let svg = render_svg(&s, Some(&r), &RenderOptions::default());
    assert_eq!(svg.matches("class=\"violator\"").count(), 1);
    assert!(svg.contains("class=\"violator\" data-id=\"b1\""));
    assert!(svg.contains(">blue_north_of_red</text>"));
    assert!(svg.contains(">0/1</text>"));
    assert!(svg.contains("green_east_of_red  [hard]"));
    assert!(svg.contains("score 0.000"));
    assert!(svg.contains("broken by b1"));
}

#[test]
fn render_to_path_picks_format_by_extension() {
    let dir = crate::support::scratch("render-to-path");
    let s = scene();
    let opts = RenderOptions::default();
    render_to_path(&s, None, &opts, &dir.join("a.svg")).unwrap();
    render_to_path(&s, None, &opts, &dir.join("a.PNG")).unwrap();
    assert!(std::fs::read_to_string(dir.join("a.svg"))
        .unwrap()
        .starts_with("<svg"));
    assert!(std::fs::read(dir.join("a.PNG"))
        .unwrap()
        .starts_with(b"\x89PNG"));
    let err = render_to_path(&s, None, &opts, &dir.join("a.jpg")).unwrap_err();
    assert!(matches!(err, RenderError::UnknownExtension { .. }));
    let msg = err.to_string();
    assert!(
        msg.contains(".jpg") && msg.contains(".svg") && msg.contains(".png"),
        "{msg}"
    );
    let err = render_to_path(&s, None, &opts, &dir.join("noext")).unwrap_err();
    assert!(err.to_string().contains("no extension"), "{err}");
    assert!(!dir.join("a.jpg").exists());
    let bad = RenderOptions {
        scale: f64::NAN,
        ..RenderOptions::default()
    };
    assert!(matches!(
        render_to_path(&s, None, &bad, &dir.join("b.svg")),
        Err(RenderError::Scale(_))
    ));
    assert!(matches!(
        render_png(&s, None, &bad),
        Err(RenderError::Scale(_))
    ));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn huge_png_is_an_error_not_a_crash() {
    let s = Scene::from_json(r#"{"space":{"width":100000,"height":100000},"objects":[]}"#).unwrap();
    let svg = render_svg(&s, None, &RenderOptions::default());
    assert!(
        !svg.contains("class=\"grid\""),
        "grid lines are skipped when too many"
    );
    assert!(matches!(
        render_png(&s, None, &RenderOptions::default()),
        Err(RenderError::TooLarge { .. })
    ));
}

#[test]
fn box_packing_pictures() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/box-packing");
    let demos =
        scenes_from_json(&std::fs::read_to_string(root.join("demos.json")).unwrap()).unwrap();
    let problem =
        Scene::from_json(&std::fs::read_to_string(root.join("problem.json")).unwrap()).unwrap();
    // A rule every demo keeps and one they all break (blue south of red).
    let atom = |d| {
        Formula::Atom(Atom::new(
            Relation::new(Kind::DR, d),
            "B",
            Target::Class("R".into()),
        ))
    };
    let rules = RuleSet::new(vec![
        Rule::new("blue_north_of_red", atom(Dir::N)),
        Rule::new("blue_south_of_red", atom(Dir::S)),
    ]);
    let opts = RenderOptions {
        scale: 1.0,
        title: Some("demos.json [0]".into()),
        ..RenderOptions::default()
    };
    let svg = render_svg(&demos[0], Some(&rules), &opts);
    let blues = demos[0].objects.iter().filter(|o| o.class == "B").count();
    assert_eq!(svg.matches("class=\"violator\"").count(), blues);
    let png = render_png(&demos[0], Some(&rules), &opts).unwrap();
    let psvg = render_svg(&problem, None, &opts);
    assert!(psvg.contains("unplaced (9)"));
    if let Some(dir) = out_dir() {
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("demo0.png"), png).unwrap();
        std::fs::write(dir.join("demo0.svg"), svg).unwrap();
        for (i, d) in demos.iter().enumerate() {
            let o = RenderOptions {
                scale: 2.0,
                title: Some(format!("demos.json [{i}]")),
                ..RenderOptions::default()
            };
            render_to_path(d, None, &o, &dir.join(format!("demo{i}_x2.png"))).unwrap();
        }
        render_to_path(&problem, None, &opts, &dir.join("problem.png")).unwrap();
        let o2 = RenderOptions {
            scale: 2.0,
            ..opts.clone()
        };
        render_to_path(
            &demos[3],
            Some(&rules),
            &o2,
            &dir.join("demo3_rules_x2.png"),
        )
        .unwrap();
        render_to_path(
            &s_small(),
            Some(&self::rules()),
            &o2,
            &dir.join("small.png"),
        )
        .unwrap();
    }
}

fn s_small() -> Scene {
    scene()
}

/// `--like`: every movable object of the like-scenes is shaded in its
/// class's colour under the layout (a position shown twice, twice); fixed
/// objects are not.
#[test]
fn like_scenes_are_shaded_under_the_layout() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/box-packing");
    let demos =
        scenes_from_json(&std::fs::read_to_string(dir.join("demos.json")).unwrap()).unwrap();
    let problem =
        Scene::from_json(&std::fs::read_to_string(dir.join("problem.json")).unwrap()).unwrap();
    let like = rccpack::resemblance::ResemblanceTarget::new(&demos);
    let svg = render_svg(
        &problem,
        None,
        &RenderOptions {
            like: Some(like),
            ..Default::default()
        },
    );
    let movable: usize = demos
        .iter()
        .map(|d| d.objects.iter().filter(|o| !o.fixed).count())
        .sum();
    assert_eq!(svg.matches("class=\"shown\"").count(), movable);
    for class in ["R", "G", "B"] {
        assert!(svg.contains(&format!("data-class=\"{class}\"")));
    }
    assert!(!svg.contains("data-class=\"W\""));
    assert!(svg.contains("shaded: where the demonstrations put each class"));
    // The shading comes before (under) the objects.
    assert!(svg.find("class=\"like\"").unwrap() < svg.find("class=\"objects\"").unwrap());
    let plain = render_svg(&problem, None, &RenderOptions::default());
    assert!(!plain.contains("class=\"shown\""));
}

/// The PNG size error names the limit hit: a side (a 100 000 × 10 table),
/// or the pixels in all (9 000 × 9 000); drawn to fit, both fit.
#[test]
fn png_too_large_names_the_limit_hit() {
    let wide = Scene::from_json(r#"{"space":{"width":100000,"height":10},"objects":[]}"#).unwrap();
    let e = render_png(&wide, None, &RenderOptions::default()).unwrap_err();
    assert!(e.to_string().contains("at most 32000 pixels a side"), "{e}");
    let square =
        Scene::from_json(r#"{"space":{"width":9000,"height":9000},"objects":[]}"#).unwrap();
    let e = render_png(&square, None, &RenderOptions::default()).unwrap_err();
    assert!(
        e.to_string().contains("at most 67108864 pixels in all"),
        "{e}"
    );
    for s in [&wide, &square] {
        let (png, scale) =
            rccpack::render::render_png_to_fit(s, None, &RenderOptions::default()).unwrap();
        assert!(scale < 1.0, "{scale}");
        let be = |i: usize| {
            u64::from(u32::from_be_bytes([
                png[i],
                png[i + 1],
                png[i + 2],
                png[i + 3],
            ]))
        };
        let (w, h) = (be(16), be(20));
        assert!(w <= 32_000 && h <= 32_000 && w * h <= 64 << 20, "{w}x{h}");
        assert!(
            w * h > 16 << 20 || w > 16_000,
            "not shrunk more than needed: {w}x{h}"
        );
    }
}
