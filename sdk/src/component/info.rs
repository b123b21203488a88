//! The component table's row type: what the definitions say of each component
//! interface, generated into [`crate::components::COMPONENTS`] and into each component
//! module (`INFO`, `ID`).

/// One component interface of the definitions: its row of the generated
/// `COMPONENTS` table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ComponentInfo {
    /// PascalCase name (`GlobalPoseSensor`), the trait's name.
    pub name: &'static str,
    /// Module name (`global_pose_sensor`): `jaus::components::global_pose_sensor`.
    pub module: &'static str,
    /// Component id (Part 1).
    pub id: u8,
    /// The Part 1 function text.
    pub function: &'static str,
    /// The SDK's stock implementation, if it ships one (the component's `stock:`).
    pub stock: Option<StockInfo>,
}

/// The SDK's stock implementation of a component, as its definition describes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct StockInfo {
    /// Its name in a node file's `host:` list (`world_model`).
    pub name: &'static str,
    /// The hardware it runs over.
    pub needs: Hardware,
}

/// The hardware a stock component runs over (`stock.needs` in the definitions).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Hardware {
    /// None: it works on messages alone (a driver above the Primitive Driver, a store).
    None,
    /// The vehicle: its actuators, or its pose and velocity.
    Vehicle,
    /// A range scanner on the vehicle.
    Scanner,
    /// A pan/tilt camera on the vehicle.
    Camera,
    /// A manipulator arm: its joints' actuators and sensors.
    Arm,
    /// Data links to other subsystems (a radio, a tether).
    Links,
}

impl Hardware {
    /// The name as written in the definitions (`vehicle`).
    pub fn name(self) -> &'static str {
        match self {
            Hardware::None => "none",
            Hardware::Vehicle => "vehicle",
            Hardware::Scanner => "scanner",
            Hardware::Camera => "camera",
            Hardware::Arm => "arm",
            Hardware::Links => "links",
        }
    }
}

impl std::fmt::Display for Hardware {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
