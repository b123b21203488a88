//! AS-4 Digital Video through the gateway, on simulated time: an AS-4 client configures
//! the demo vehicle's RA 3.3 camera as a video sensor and plays, pauses and stops its
//! stream; the frames the service publishes to the node's video hub (which the node
//! serves as MJPEG over HTTP) are real JPEG images of the camera, at the rate asked for;
//! what is not the controlling client's to do, or beyond the bounds, is refused.

use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;
use jaus::Address;
use jaus_as4::environment::video::{Next, StreamState};
use jaus_as4::environment::{VideoHub, VideoLimits};
use jaus_as4::gateway::GatewayConfig;
use jaus_as4::{
    ConfirmSensorConfigurationVariant as Confirmed,
    ConfirmSensorConfigurationVariantDigitalVideoSensorErrorRecErrorCode as Code,
    ControlDigitalVideoSensorStream, ControlDigitalVideoSensorStreamStreamState as Stream,
    DigitalFormatEnum, DigitalVideoSensorConfigurationRec, FrameSizeEnum, Message,
    QueryDigitalVideoSensorCapabilities, QueryDigitalVideoSensorCapabilitiesRec,
    QueryDigitalVideoSensorConfiguration, QueryDigitalVideoSensorConfigurationConfigurationRec,
    ReleaseControl, RequestIdRec, SetDigitalVideoSensorConfiguration,
};

mod common;
use common::as4::As4Rig;

struct Rig {
    rig: As4Rig,
    hub: VideoHub,
}

impl Rig {
    /// The demo vehicle behind its gateway, with a video hub (8 frames/s at most).
    fn new() -> Self {
        let t0 = Instant::now();
        let node =
            jaus_sim::demo::vehicle_node(t0, jaus::net::NodeConfig::default(), 1, 1).unwrap();
        let hub = VideoHub::new(2);
        let mut config = GatewayConfig::new(
            As4Id::new(1, 1, 1),
            Address::new(1, 1, 60, 1),
            1,
            "demo vehicle",
        );
        let limits = VideoLimits {
            max_frame_rate: 8,
            ..VideoLimits::default()
        };
        config.video = Some((hub.clone(), limits));
        let rig = As4Rig::configured(t0, node, Vec::new(), config, Duration::from_secs(3));
        Rig { rig, hub }
    }

    fn stream(&mut self, s: Stream) {
        let got = self.rig.ask(
            ControlDigitalVideoSensorStream {
                sensor_id: 1,
                stream_state: s,
            },
            Duration::from_millis(50),
        );
        assert!(got.is_empty(), "{got:?}");
    }

    fn configure(&mut self, rec: DigitalVideoSensorConfigurationRec) -> Confirmed {
        let Message::ConfirmSensorConfiguration(mut c) =
            self.rig.one(SetDigitalVideoSensorConfiguration {
                request_id_rec: RequestIdRec { request_id: 3 },
                digital_video_sensor_list: vec![rec],
            })
        else {
            panic!("no Confirm Sensor Configuration");
        };
        assert_eq!(c.request_id_rec.request_id, 3);
        c.confirm_sensor_list.remove(0)
    }

    fn published(&self) -> u64 {
        self.hub.stats(1).expect("sensor 1's stream").published
    }
}

fn rate(frame_rate: u8) -> DigitalVideoSensorConfigurationRec {
    DigitalVideoSensorConfigurationRec {
        sensor_id: 1,
        frame_rate: Some(frame_rate),
        ..Default::default()
    }
}

fn code(c: &Confirmed) -> Code {
    match c {
        Confirmed::DigitalVideoSensorErrorRec(e) => e.digital_video_error_code,
        other => panic!("refusal expected, got {other:?}"),
    }
}

#[test]
fn a_client_plays_the_camera_as_mjpeg_frames_at_the_rate_it_asks_pauses_and_stops() {
    let mut r = Rig::new();
    // Offered with its capabilities: MJPEG, 1 to 8 frames/s.
    assert!(r
        .rig
        .service_uris()
        .iter()
        .any(|u| u == "urn:jaus:jss:environmentSensing:DigitalVideo"));
    let Message::ReportDigitalVideoSensorCapabilities(c) =
        r.rig.one(QueryDigitalVideoSensorCapabilities {
            query_digital_video_sensor_capabilities_list: vec![
                QueryDigitalVideoSensorCapabilitiesRec {
                    sensor_id: 1,
                    query_presence_vector: 0xFF,
                },
            ],
        })
    else {
        panic!("no capabilities");
    };
    let cap = &c.digital_video_sensor_list[0];
    assert_eq!(
        (cap.minimum_frame_rate, cap.maximum_frame_rate),
        (Some(1), Some(8))
    );
    assert!(cap
        .supported_digital_formats
        .as_ref()
        .is_some_and(|f| f.mjpeg && !f.mpeg2));

    // Not the controlling client's: refused, nothing plays.
    let refused = r.rig.refused();
    r.stream(Stream::Play);
    assert_eq!(r.rig.refused(), refused + 1);
    r.rig.net.run_for(Duration::from_secs(1));
    assert_eq!(
        (r.hub.state(1), r.published()),
        (Some(StreamState::Stopped), 0)
    );

    r.rig.take_control();
    // Beyond the bounds, sensor by sensor, with the reason.
    assert_eq!(code(&r.configure(rate(30))), Code::InvalidMaximumFrameRate);
    assert_eq!(code(&r.configure(rate(0))), Code::InvalidMinimumFrameRate);
    let both = r.configure(DigitalVideoSensorConfigurationRec {
        sensor_id: 1,
        frame_size: Some(FrameSizeEnum::V640x480Vga),
        digital_format: Some(DigitalFormatEnum::Mpeg2),
        ..Default::default()
    });
    assert_eq!(code(&both), Code::MultipleInvalidParameters);
    assert!(matches!(r.configure(rate(4)), Confirmed::SensorIdRec(_)));
    let Message::ReportDigitalVideoSensorConfiguration(cfg) =
        r.rig.one(QueryDigitalVideoSensorConfiguration {
            query_digital_video_configuration_list: vec![
                QueryDigitalVideoSensorConfigurationConfigurationRec {
                    sensor_id: 1,
                    ..Default::default()
                },
            ],
        })
    else {
        panic!("no configuration");
    };
    let cfg = &cfg.digital_video_sensor_configuration_list[0];
    assert_eq!(
        (cfg.frame_rate, cfg.digital_format),
        (Some(4), Some(DigitalFormatEnum::Mjpeg))
    );

    // Playing at 4 frames/s for 3 s (simulated): 12 frames, each a JPEG of the camera.
    let mut viewer = r.hub.watch(1).expect("a viewer");
    r.stream(Stream::Play);
    let mut frames = Vec::new();
    for _ in 0..60 {
        r.rig.net.run_for(Duration::from_millis(50));
        if let Next::Frame(f) = viewer.next(Duration::ZERO) {
            frames.push(f);
        }
    }
    let n = r.published();
    assert!((11..=13).contains(&n), "{n} frames in 3 s at 4 frames/s");
    assert_eq!(
        frames.len() as u64,
        n,
        "a viewer as fast as the stream misses none"
    );
    let spacing: Vec<Duration> = frames.windows(2).map(|w| w[1].at - w[0].at).collect();
    for s in &spacing {
        assert!(
            (Duration::from_millis(200)..=Duration::from_millis(300)).contains(s),
            "{spacing:?}"
        );
    }
    let mut d = jpeg_decoder::Decoder::new(&*frames[0].jpeg);
    let pixels = d.decode().expect("a JPEG");
    let info = d.info().expect("its header");
    // The size of the RA 3.3 camera's own image (its PNG, decoded).
    let env = r.rig.dual().gateway().node().env();
    let vs = env.targets().visual_sensor.expect("the camera found");
    let Some((_, jaus::messages::Message::ReportImage(png))) =
        env.latest(vs, <jaus::messages::ReportImage as jaus::JausMessage>::CODE)
    else {
        panic!("no RA 3.3 image");
    };
    let rgb =
        jaus::stock::environment::image::decode(png.video_format, &png.data, 1 << 24).unwrap();
    assert_eq!((info.width, info.height), (rgb.width, rgb.height));
    assert_eq!((rgb.width, rgb.height), (640, 480));
    assert_eq!(pixels.len(), 640 * 480 * 3);
    println!(
        "{n} frames in 3 s; the first {} bytes of JPEG",
        frames[0].jpeg.len()
    );

    // Paused: no frames; played again: frames again, at the new rate.
    r.stream(Stream::Pause);
    let paused = r.published();
    r.rig.net.run_for(Duration::from_secs(1));
    assert_eq!(
        (r.hub.state(1), r.published()),
        (Some(StreamState::Paused), paused)
    );
    assert!(matches!(r.configure(rate(8)), Confirmed::SensorIdRec(_)));
    r.stream(Stream::Play);
    r.rig.net.run_for(Duration::from_secs(1));
    let more = r.published() - paused;
    assert!(
        (7..=9).contains(&more),
        "{more} frames in 1 s at 8 frames/s"
    );

    // Stopped: the viewer is told, the frame forgotten, nothing more published.
    r.stream(Stream::Stop);
    assert_eq!(viewer.next(Duration::from_secs(1)), Next::Stopped);
    let stopped = r.published();
    r.rig.net.run_for(Duration::from_secs(1));
    assert_eq!((r.published(), r.hub.latest(1)), (stopped, None));
    assert_eq!(r.hub.stats(1).unwrap().dropped, 0);
}

#[test]
fn the_stream_stops_when_its_client_lets_go_of_control() {
    let mut r = Rig::new();
    r.rig.take_control();
    r.stream(Stream::Play);
    r.rig.net.run_for(Duration::from_secs(1));
    assert_eq!(r.hub.state(1), Some(StreamState::Playing));
    assert!(r.published() >= 4, "{}", r.published());
    r.rig.ask(ReleaseControl {}, Duration::from_millis(300));
    assert_eq!(r.hub.state(1), Some(StreamState::Stopped));
    let n = r.published();
    r.rig.net.run_for(Duration::from_secs(1));
    assert_eq!(r.published(), n);
}
