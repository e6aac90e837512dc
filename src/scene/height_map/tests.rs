//! Tests of [`HeightMap`] itself, and of reading and
//! querying maps through several of its parts together.

use super::npy::tests::{le8, npy, sample_values};
use super::{HeightMap, HeightMapError};

#[test]
fn nan_is_named_by_row_and_column() {
    let text = "1 2 3 4\n5 6 7 8\n9 nan 11 12\n13 14 15 16\n";
    let err = HeightMap::from_text(text, 1.0, "n.txt").unwrap_err();
    assert!(matches!(
        err,
        HeightMapError::NonFiniteHeight { row: 3, column: 2, ref file, value }
            if file == "n.txt" && value.is_nan()
    ));
    let text = err.to_string();
    assert!(text.contains("row 3, column 2") && text.contains("NaN") && text.contains("n.txt"));

    let mut heights: Vec<f64> = (0..16).map(f64::from).collect();
    heights[4 * 3 + 1] = f64::NEG_INFINITY;
    let err = HeightMap::new(4, 4, 1.0, heights).unwrap_err();
    assert!(matches!(
        err,
        HeightMapError::NonFiniteHeight {
            row: 4,
            column: 2,
            ..
        }
    ));
    assert!(err.to_string().contains("infinite"));
}

#[test]
fn new_refuses_bad_arguments() {
    let good: Vec<f64> = (0..16).map(f64::from).collect();
    assert!(HeightMap::new(4, 4, 1.0, good.clone()).is_ok());
    assert!(matches!(
        HeightMap::new(3, 4, 1.0, vec![0.0; 12]),
        Err(HeightMapError::Dimensions { nx: 3, ny: 4, .. })
    ));
    assert!(matches!(
        HeightMap::new(16385, 4, 1.0, Vec::new()),
        Err(HeightMapError::Dimensions { nx: 16385, .. })
    ));
    assert_eq!(
        HeightMap::new(4, 4, 1.0, vec![1.0; 15]),
        Err(HeightMapError::LengthMismatch {
            file: String::new(),
            expected: 16,
            found: 15
        })
    );
    for spacing in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e31, 1e-31] {
        assert!(matches!(
            HeightMap::new(4, 4, spacing, good.clone()),
            Err(HeightMapError::Spacing { .. })
        ));
    }
    let mut huge = good.clone();
    huge[5] = -2e30;
    assert!(matches!(
        HeightMap::new(4, 4, 1.0, huge),
        Err(HeightMapError::HeightOutOfRange {
            row: 2,
            column: 2,
            ..
        })
    ));
    let err = HeightMap::new(4, 4, 1.0, vec![2.5; 16]).unwrap_err();
    assert_eq!(
        err,
        HeightMapError::Flat {
            file: String::new(),
            height: 2.5
        }
    );
    assert!(err.to_string().contains("flat"));
}

#[test]
fn sample_is_exact_on_a_plane_and_at_nodes() {
    let (nx, ny, spacing) = (7, 5, 0.3);
    let plane = |x: f64, y: f64| 2.0 + 0.7 * x - 1.3 * y;
    let mut heights = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let x = (i as f64 - 3.0) * spacing;
            let y = (j as f64 - 2.0) * spacing;
            heights.push(plane(x, y));
        }
    }
    let map = HeightMap::new(nx, ny, spacing, heights).unwrap();
    let min = map.min_height();
    assert!((min - plane(-0.9, 0.6)).abs() < 1e-12);
    for (x, y) in [
        (0.0, 0.0),
        (0.123, -0.456),
        (-0.899, 0.599),
        (0.9, -0.6),
        (-0.9, 0.6),
    ] {
        let got = map.sample(x, y).unwrap();
        assert!(
            (got - (plane(x, y) - min)).abs() < 1e-12,
            "({x}, {y}): {got}"
        );
        assert!(got >= 0.0);
    }
    for j in 0..ny {
        for i in 0..nx {
            let x = (i as f64 - 3.0) * spacing;
            let y = (j as f64 - 2.0) * spacing;
            let got = map.sample(x, y).unwrap();
            assert!((got - (map.heights()[j * nx + i] - min)).abs() < 1e-12);
        }
    }
    let (ex, ey) = map.extent();
    assert!((ex - 0.9).abs() < 1e-15 && (ey - 0.6).abs() < 1e-15);
    assert!(map.sample(ex, ey).is_some() && map.sample(-ex, -ey).is_some());
    assert_eq!(map.sample(ex * 1.001, 0.0), None);
    assert_eq!(map.sample(0.0, -ey * 1.001), None);
    assert_eq!(map.sample(f64::NAN, 0.0), None);
    assert_eq!(map.sample(0.0, f64::INFINITY), None);
}

#[test]
fn lowest_point_is_the_minimum_node() {
    let mut heights = vec![1.0; 6 * 4];
    heights[2 * 6 + 4] = -3.0; // i = 4, j = 2
    let map = HeightMap::new(6, 4, 2.0, heights).unwrap();
    assert_eq!(map.min_height(), -3.0);
    assert_eq!(map.lowest_point(), (3.0, 1.0));
    assert_eq!(map.sample(3.0, 1.0), Some(0.0));
    assert_eq!(map.sample(-5.0, -3.0), Some(4.0));
}

#[test]
fn shifted_map_samples_identically() {
    // Heights on a 1/64 grid so that adding 7 is exact.
    let heights: Vec<f64> = (0..48).map(|k| f64::from((k * 37) % 29) / 64.0).collect();
    let shifted: Vec<f64> = heights.iter().map(|h| h + 7.0).collect();
    let a = HeightMap::new(8, 6, 0.5, heights).unwrap();
    let b = HeightMap::new(8, 6, 0.5, shifted).unwrap();
    assert_eq!(b.min_height(), a.min_height() + 7.0);
    assert_eq!(a.lowest_point(), b.lowest_point());
    for (x, y) in [(0.0, 0.0), (-1.75, 1.25), (1.1, -0.3), (0.37, 0.91)] {
        assert_eq!(a.sample(x, y), b.sample(x, y));
        assert!(a.sample(x, y).is_some());
    }
    assert_eq!(
        a.curvature_fit(1.2).map(|f| f.kxx),
        b.curvature_fit(1.2).map(|f| f.kxx)
    );
}

#[test]
fn read_dispatches_on_extension() {
    let dir = std::env::temp_dir();
    let stem = format!("height_map_test_{}", std::process::id());
    let (_, _, values) = sample_values();
    let npy_path = dir.join(format!("{stem}.NPY"));
    std::fs::write(&npy_path, npy("<f8", "(4, 5)", false, 1, &le8(&values))).unwrap();
    let text_path = dir.join(format!("{stem}.txt"));
    std::fs::write(&text_path, "0 1 2 3\n1 2 3 4\n2 3 4 5\n3 4 5 9\n").unwrap();
    let from_npy = HeightMap::read(&npy_path, 1.0);
    let from_text = HeightMap::read(&text_path, 1.0);
    let missing = HeightMap::read(&dir.join(format!("{stem}_missing.txt")), 1.0);
    let _ = std::fs::remove_file(&npy_path);
    let _ = std::fs::remove_file(&text_path);
    assert_eq!(from_npy.unwrap().heights(), values.as_slice());
    assert_eq!(from_text.unwrap().heights()[15], 9.0);
    let err = missing.unwrap_err();
    assert!(matches!(err, HeightMapError::Io { .. }));
    assert!(err.to_string().contains("_missing.txt"));
}
