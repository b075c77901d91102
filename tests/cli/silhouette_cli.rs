//! `goniolight silhouette` and `goniolight bench silhouette` contracts and bad input.

use crate::common;

use common::{root, run_cli};

fn model(name: &str) -> String {
    root()
        .join("assets/models")
        .join(name)
        .display()
        .to_string()
}

#[test]
fn json_edges_use_obj_vertex_indices() {
    for method in ["brute", "hextree"] {
        let (code, out, err) = run_cli(
            &[
                "silhouette",
                &model("box.obj"),
                "--light",
                "0,0,1,0",
                "--method",
                method,
                "--json",
            ],
            "",
        );
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        // Lit from above: the top face's four edges (OBJ vertices 5–8, 0-based 4–7).
        assert_eq!(v["count"], 4);
        assert_eq!(
            v["edges"],
            serde_json::json!([[4, 5], [4, 6], [5, 7], [6, 7]])
        );
    }
    // Duplicate vertices are welded and reported by their smallest OBJ index.
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("dup.obj");
    std::fs::write(
        &obj,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nf 4 5 3\n",
    )
    .unwrap();
    let (code, out, _) = run_cli(
        &[
            "silhouette",
            obj.to_str().unwrap(),
            "--light",
            "0.2,0.3,5,1",
            "--json",
        ],
        "",
    );
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        v["edges"],
        serde_json::json!([[0, 1], [0, 2], [1, 4], [2, 4]])
    );
}

#[test]
fn brute_and_hextree_print_the_same_edges_for_every_bundled_model() {
    for name in [
        "torus.obj",
        "terrain_patch.obj",
        "building.obj",
        "fins.obj",
        "flipped_box.obj",
    ] {
        for light in ["3,2,6,1", "-0.3,0.2,0.5,0"] {
            let run = |m: &str| {
                run_cli(
                    &[
                        "silhouette",
                        &model(name),
                        "--light",
                        light,
                        "--method",
                        m,
                        "--json",
                    ],
                    "",
                )
            };
            let (a, b) = (run("brute"), run("hextree"));
            assert_eq!(a.0, 0, "{}", a.2);
            assert_eq!(a.1, b.1, "{name} {light}");
        }
    }
}

#[test]
fn bad_input_exits_2_naming_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: &str| {
        let p = dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        p.display().to_string()
    };
    let empty = write("empty.obj", "# nothing\n");
    let broken = write("broken.obj", "v 0 0 0\nv 1 zero 0\n");
    let degenerate = write("line.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec![model("box.obj"), "--light".into(), "nan,0,0,1".into()],
            "not finite",
        ),
        (
            vec![model("box.obj"), "--light".into(), "1,2,3".into()],
            "4 numbers",
        ),
        (
            vec![model("box.obj"), "--light".into(), "0,0,0,0".into()],
            "non-zero direction",
        ),
        (
            vec!["missing.obj".into(), "--light".into(), "0,0,1,0".into()],
            "missing.obj",
        ),
        (
            vec![empty.clone(), "--light".into(), "0,0,1,0".into()],
            "no triangles with an area",
        ),
        (
            vec![broken.clone(), "--light".into(), "0,0,1,0".into()],
            "line 2",
        ),
        (
            vec![degenerate.clone(), "--light".into(), "0,0,1,0".into()],
            "degenerate",
        ),
    ];
    for (args, text) in cases {
        let mut full = vec!["silhouette".to_string()];
        full.extend(args);
        let refs: Vec<&str> = full.iter().map(String::as_str).collect();
        let (code, out, err) = run_cli(&refs, "");
        assert_eq!(code, 2, "{full:?}: {err}");
        assert!(out.is_empty(), "{out}");
        assert!(err.contains(text), "{full:?}: {text:?} in {err}");
    }
}

#[test]
fn bench_silhouette_json_contract() {
    let (code, out, err) = run_cli(
        &[
            "bench",
            "silhouette",
            "--json",
            "--scale",
            "0.002",
            "--queries",
            "4",
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let rows = v["meshes"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    for r in rows {
        for k in ["triangles", "brute_ms", "hextree_ms", "speedup"] {
            assert!(r[k].is_number(), "{k} in {r}");
        }
        let s = r["brute_ms"].as_f64().unwrap() / r["hextree_ms"].as_f64().unwrap();
        assert!((s - r["speedup"].as_f64().unwrap()).abs() < 1e-9);
    }
}
