//! The conversions of `sensors.rs`: angles and ranges of a sweep, pixel encodings,
//! row padding, PNG, resampling, the bounds, and the counting of what is dropped.

use std::f64::consts::{FRAC_PI_2, PI};

use jaus::messages::ImageFormat;
use jaus::stock::environment::image::encode;

use super::*;

fn scan(angle_min: f32, angle_increment: f32, ranges: Vec<f32>) -> LaserScan {
    LaserScan {
        angle_min,
        angle_max: angle_min + angle_increment * (ranges.len().max(1) - 1) as f32,
        angle_increment,
        range_min: 0.1,
        range_max: 30.0,
        ranges,
        ..LaserScan::default()
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-6
}

#[test]
fn ros_counter_clockwise_angles_become_bearings_to_the_right() {
    // ROS −90° (right), 0°, +90° (left).
    let s = scan(-FRAC_PI_2 as f32, FRAC_PI_2 as f32, vec![1.0, 2.0, 3.0]);
    let mut b = Vec::new();
    scan_to_beams(&s, &mut b).unwrap();
    assert_eq!(b.len(), 3);
    // Left to right: the left beam (ROS +90°) first, at bearing −90°.
    assert!(
        close(b[0].bearing, -FRAC_PI_2) && b[0].range == Some(3.0),
        "{b:?}"
    );
    assert!(close(b[1].bearing, 0.0) && b[1].range == Some(2.0));
    assert!(close(b[2].bearing, FRAC_PI_2) && b[2].range == Some(1.0));
    // Bearings wrap to (−π, π]: a 360° scan from −π.
    let s = scan(-PI as f32, (PI / 2.0) as f32, vec![1.0; 5]);
    scan_to_beams(&s, &mut b).unwrap();
    assert!(b
        .iter()
        .all(|x| x.bearing > -PI - 1e-6 && x.bearing <= PI + 1e-6));
    let s = scan((1.5 * PI) as f32, 0.0, vec![1.0]);
    scan_to_beams(&s, &mut b).unwrap();
    assert!(close(b[0].bearing, FRAC_PI_2), "{b:?}");
}

#[test]
fn ranges_outside_the_limits_or_not_finite_are_no_return() {
    let s = scan(
        0.0,
        0.1,
        vec![
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            0.05,
            31.0,
            0.1,
            30.0,
            -1.0,
        ],
    );
    let mut b = Vec::new();
    scan_to_beams(&s, &mut b).unwrap();
    let ranges: Vec<_> = b.iter().rev().map(|x| x.range).collect();
    assert_eq!(
        ranges,
        vec![
            None,
            None,
            None,
            None,
            None,
            Some(0.1f32 as f64),
            Some(30.0),
            None
        ]
    );
    // An empty sweep is a sweep with nothing in it.
    scan_to_beams(&scan(0.0, 0.1, vec![]), &mut b).unwrap();
    assert!(b.is_empty());
}

#[test]
fn bad_sweeps_are_refused() {
    let mut b = vec![Beam {
        bearing: 0.0,
        range: None,
    }];
    let big = scan(0.0, 0.001, vec![1.0; MAX_BEAMS + 1]);
    assert_eq!(
        scan_to_beams(&big, &mut b),
        Err(SensorError::TooManyBeams {
            beams: MAX_BEAMS + 1
        })
    );
    assert!(b.is_empty(), "out is cleared");
    scan_to_beams(&scan(0.0, 0.001, vec![1.0; MAX_BEAMS]), &mut b).unwrap();
    assert_eq!(b.len(), MAX_BEAMS);
    let mut s = scan(f32::NAN, 0.1, vec![1.0]);
    assert!(matches!(
        scan_to_beams(&s, &mut b),
        Err(SensorError::BadScan(_))
    ));
    s.angle_min = 0.0;
    s.range_max = 0.05;
    assert!(matches!(
        scan_to_beams(&s, &mut b),
        Err(SensorError::BadScan(_))
    ));
    s.range_max = f32::INFINITY;
    assert!(scan_to_beams(&s, &mut b).is_err());
}

/// A `w`×`h` image in `encoding` whose RGB pixel (x, y) is `rgb(x, y)`, rows `pad`
/// bytes longer than the pixels (filled with 0xEE).
fn image(encoding: &str, w: u32, h: u32, pad: usize) -> Image {
    let bpp = match encoding {
        "rgb8" | "bgr8" => 3,
        "rgba8" | "bgra8" => 4,
        "mono16" => 2,
        _ => 1,
    };
    let step = w as usize * bpp + pad;
    let mut data = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let [r, g, b] = rgb(x, y);
            match encoding {
                "rgb8" => data.extend([r, g, b]),
                "bgr8" => data.extend([b, g, r]),
                "rgba8" => data.extend([r, g, b, 7]),
                "bgra8" => data.extend([b, g, r, 7]),
                "mono16" => data.extend([r, 0x11]),
                _ => data.push(r),
            }
        }
        data.extend(std::iter::repeat_n(0xEE, pad));
    }
    Image {
        width: w,
        height: h,
        encoding: encoding.into(),
        is_bigendian: u8::from(encoding == "mono16"),
        step: step as u32,
        data,
        ..Image::default()
    }
}

fn rgb(x: u32, y: u32) -> [u8; 3] {
    [(x * 40) as u8, (y * 50) as u8, 200]
}

const LIMIT: usize = 16 << 20;

#[test]
fn encodings_and_row_padding_become_rgb() {
    for (enc, grey) in [
        ("rgb8", false),
        ("bgr8", false),
        ("rgba8", false),
        ("bgra8", false),
        ("mono8", true),
        ("mono16", true),
    ] {
        for pad in [0, 2] {
            let img = image_to_rgb(&image(enc, 4, 3, pad), LIMIT).unwrap();
            assert_eq!((img.width, img.height), (4, 3));
            for (x, y) in [(0, 0), (3, 0), (1, 2), (3, 2)] {
                let [r, g, b] = rgb(x, y);
                let want = if grey { [r; 3] } else { [r, g, b] };
                assert_eq!(
                    img.get(x as usize, y as usize),
                    Some(want),
                    "{enc} pad {pad}"
                );
            }
        }
    }
    // Little-endian 16-bit grey: the high byte is the second.
    let mut i = image("mono16", 1, 1, 0);
    i.is_bigendian = 0;
    assert_eq!(image_to_rgb(&i, LIMIT).unwrap().pixels, vec![0x11; 3]);
    // The last row may lack its padding.
    let mut i = image("rgb8", 2, 2, 4);
    i.data.truncate(i.data.len() - 4);
    assert!(image_to_rgb(&i, LIMIT).is_ok());
}

#[test]
fn bad_images_are_refused_with_the_reason() {
    let e = check_image(
        &Image {
            encoding: "yuv422".into(),
            ..image("rgb8", 2, 2, 0)
        },
        LIMIT,
    )
    .unwrap_err();
    assert_eq!(e, SensorError::Encoding("yuv422".into()));
    assert!(e.to_string().contains("yuv422"));
    let mut i = image("rgb8", 4, 3, 0);
    i.step = 11;
    assert_eq!(
        check_image(&i, LIMIT),
        Err(SensorError::Step { step: 11, row: 12 })
    );
    let mut i = image("rgb8", 4, 3, 0);
    i.data.pop();
    assert_eq!(
        image_to_rgb(&i, LIMIT),
        Err(SensorError::Short {
            len: 35,
            needed: 36
        })
    );
    let mut i = image("rgb8", 4, 3, 0);
    i.step = u32::MAX;
    assert!(matches!(
        check_image(&i, LIMIT),
        Err(SensorError::Short { .. })
    ));
    assert!(matches!(
        check_image(&image("mono8", 0, 3, 0), LIMIT),
        Err(SensorError::Empty { .. })
    ));
    // Too wide (no pixels needed to tell), or over the byte limit.
    let wide = Image {
        width: MAX_IMAGE_SIDE + 1,
        ..image("mono8", 1, 1, 0)
    };
    assert!(matches!(
        check_image(&wide, LIMIT),
        Err(SensorError::TooLarge { .. })
    ));
    let i = image("mono8", 40, 40, 0);
    assert!(check_image(&i, 40 * 40 * 3).is_ok());
    assert!(matches!(
        check_image(&i, 40 * 40 * 3 - 1),
        Err(SensorError::TooLarge { .. })
    ));
}

#[test]
fn png_files_decode_and_other_formats_are_refused() {
    let mut img = RgbImage::filled(5, 4, [1, 2, 3]);
    img.put(4, 3, [250, 0, 9]);
    let png = encode(&img, ImageFormat::Png).unwrap();
    assert_eq!(png_to_rgb(&png, LIMIT).unwrap(), img);
    let c = |format: &str| CompressedImage {
        format: format.into(),
        data: png.clone(),
        ..CompressedImage::default()
    };
    assert!(check_compressed(&c("png"), LIMIT).is_ok());
    assert!(check_compressed(&c("rgb8; png compressed bgr8"), LIMIT).is_ok());
    assert_eq!(
        check_compressed(&c("jpeg"), LIMIT),
        Err(SensorError::Format("jpeg".into()))
    );
    assert!(matches!(
        check_compressed(&c("png"), 10),
        Err(SensorError::TooLarge { .. })
    ));
    assert!(matches!(
        png_to_rgb(b"not a png", LIMIT),
        Err(SensorError::Png(_))
    ));
    assert!(matches!(
        png_to_rgb(&png[..png.len() - 20], LIMIT),
        Err(SensorError::Png(_))
    ));
    // Too wide: refused from the header, before decoding.
    let wide = encode(&RgbImage::filled(5000, 1, [0; 3]), ImageFormat::Png).unwrap();
    assert!(matches!(
        png_to_rgb(&wide, LIMIT),
        Err(SensorError::TooLarge { width: 5000, .. })
    ));
}

#[test]
fn resampling_takes_the_nearest_pixel() {
    let mut img = RgbImage::filled(2, 2, [0; 3]);
    img.put(1, 0, [10; 3]);
    img.put(0, 1, [20; 3]);
    img.put(1, 1, [30; 3]);
    let up = resample(img.clone(), 4, 4);
    assert_eq!((up.width, up.height, up.pixels.len()), (4, 4, 48));
    assert_eq!(up.get(3, 0), Some([10; 3]));
    assert_eq!(up.get(1, 3), Some([20; 3]));
    assert_eq!(up.get(2, 2), Some([30; 3]));
    let down = resample(img.clone(), 1, 1);
    assert_eq!(down.pixels, vec![0; 3]);
    assert_eq!(resample(img.clone(), 2, 2), img);
}

#[test]
fn drops_are_counted_and_old_data_is_none() {
    let tap = Tap::detached();
    on_scan(
        &tap.shared,
        &scan(0.0, 0.1, vec![1.0; MAX_BEAMS + 1]),
        "scan",
    );
    on_scan(&tap.shared, &scan(0.0, 0.1, vec![2.0, 2.0]), "scan");
    on_frame(
        &tap.shared,
        Frame::Raw(Image {
            encoding: "yuv422".into(),
            ..image("rgb8", 2, 2, 0)
        }),
        LIMIT,
        "image_raw",
    );
    on_compressed(
        &tap.shared,
        CompressedImage {
            format: "jpeg".into(),
            ..CompressedImage::default()
        },
        LIMIT,
        "image_raw",
    );
    on_frame(&tap.shared, Frame::Raw(image("bgr8", 4, 3, 1)), LIMIT, "x");
    let st = lock(&tap.shared).stats;
    assert_eq!(
        (st.scans, st.scans_refused, st.images, st.images_refused),
        (1, 1, 1, 2)
    );

    let config = Ros2Config::default();
    let mut scanner = ScanSource::new(tap.clone(), &config.sensors);
    let mut out = Vec::new();
    let now = Instant::now();
    assert!(scanner.scan(now, &mut out));
    assert_eq!(out.len(), 2);
    assert!(!scanner.scan(now + Duration::from_secs(2), &mut out));
    assert!(out.is_empty());

    let mut cam = RosCamera::new(tap.clone(), &config, "rt/image_raw".into());
    assert_eq!(cam.specs()[0].resolution.1, (640, 480));
    let mut s = CameraSettings::defaults_for(&cam.specs()[0]);
    (s.width, s.height) = (4, 3);
    let img = cam.capture(0, now, &s).unwrap();
    assert_eq!(img.get(3, 2), Some(rgb(3, 2)));
    assert_eq!(cam.capture(1, now, &s), None);
    assert_eq!(cam.capture(0, now + Duration::from_secs(2), &s), None);
    (s.width, s.height) = (8, 6);
    assert_eq!(cam.capture(0, now, &s).unwrap().get(7, 5), Some(rgb(3, 2)));
    // A PNG that does not decode: counted once, then no frame until the next.
    on_compressed(
        &tap.shared,
        CompressedImage {
            format: "png".into(),
            data: b"garbage".to_vec(),
            ..CompressedImage::default()
        },
        LIMIT,
        "c",
    );
    assert_eq!(cam.capture(0, now, &s), None);
    assert_eq!(cam.capture(0, now, &s), None);
    assert_eq!(lock(&tap.shared).stats.images_refused, 3);
}
