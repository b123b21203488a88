"""Type stubs of the package ``jaus``, GENERATED from the SDK's message definitions
by ``jaus._jaus._stubs()`` (sdk/py/src/stubs.rs): do not edit; the pytest suite checks
this file is up to date (``UPDATE_GOLDEN=1`` rewrites it).

Each message is a class here (``jaus.ReportGlobalPose``): at run time calling it builds
the message (``jaus.message(NAME, **fields)``) and ``isinstance`` checks the message's
name; every message object is a ``jaus.Message``."""

from typing import Any, AsyncIterator, Dict, Generic, Iterator, List, Literal, Mapping, Optional, TypeVar, Union, overload

from ._jaus import Address as Address
from ._jaus import ClientError as ClientError
from ._jaus import Control as Control
from ._jaus import ControlRefused as ControlRefused
from ._jaus import DecodeError as DecodeError
from ._jaus import EncodeError as EncodeError
from ._jaus import JausError as JausError
from ._jaus import Message as Message
from ._jaus import Packet as Packet
from ._jaus import Record as Record
from ._jaus import Schema as Schema
from ._jaus import SpecError as SpecError
from ._jaus import Watch as Watch
from ._jaus import decode as decode
from ._jaus import decode_many as decode_many
from ._jaus import decode_packet as decode_packet
from ._jaus import doc as doc
from ._jaus import encode as encode
from ._jaus import encode_packet as encode_packet
from ._jaus import messages as messages
from ._jaus import read_pcap as read_pcap
from ._jaus import Client as _Client

_M = TypeVar("_M", bound=Message)

_RecordIn = Union[Record, Mapping[str, Any]]
"""A record, bit field or union given to a constructor: a ``jaus.Record`` or a dict of
the JSON form."""

class AsyncWatch(Generic[_M]):
    """The reports of a ``jaus.Watch`` for ``async for``; ``async with`` ends it."""

    @property
    def watch(self) -> Watch[_M]: ...
    def __aiter__(self) -> AsyncIterator[_M]: ...
    async def __anext__(self) -> _M: ...
    async def aclose(self) -> None: ...
    async def __aenter__(self) -> "AsyncWatch[_M]": ...
    async def __aexit__(self, *exc: Any) -> bool: ...

class SetDataLinkStatus(Message):
    """Sets the state of the communicator's data link (the RA calls it Set Data Link State) (code 0x0200)."""

    state: Union[Literal["Off", "On", "Standby", "LossOfCommand"], Record]
    """The new link state."""
    def __init__(self, *, state: Union[Literal["Off", "On", "Standby", "LossOfCommand"], _RecordIn] = ...) -> None: ...

class SetDataLinkSelect(Message):
    """Selects the data link the communicator uses (code 0x0201)."""

    data_link_id: int
    """The link to select."""
    def __init__(self, *, data_link_id: int = ...) -> None: ...

class SetSelectedDataLinkState(Message):
    """Sets the state of a given data link (code 0x0202)."""

    data_link_id: int
    """The link whose state is set."""
    state: Union[Literal["Off", "On", "Standby", "LossOfCommand"], Record]
    """The new link state."""
    def __init__(self, *, data_link_id: int = ..., state: Union[Literal["Off", "On", "Standby", "LossOfCommand"], _RecordIn] = ...) -> None: ...

class QueryDataLinkStatus(Message):
    """Asks for the state of a data link (code 0x2200)."""

    data_link_id: int
    """The link asked about."""
    def __init__(self, *, data_link_id: int = ...) -> None: ...

class QuerySelectedDataLinkStatus(Message):
    """Asks which data link is selected (code 0x2201)."""

    def __init__(self) -> None: ...

class QueryHeartbeatPulse(Message):
    """Asks a component for a heartbeat pulse (code 0x2202)."""

    def __init__(self) -> None: ...

class ReportDataLinkStatus(Message):
    """The state of a data link (code 0x4200)."""

    data_link_id: int
    """The link reported on."""
    data_link_state: Union[Literal["Off", "On", "Standby", "LossOfCommand"], Record]
    """Its state."""
    def __init__(self, *, data_link_id: int = ..., data_link_state: Union[Literal["Off", "On", "Standby", "LossOfCommand"], _RecordIn] = ...) -> None: ...

class ReportSelectedDataLinkStatus(Message):
    """The selected data link (code 0x4201)."""

    data_link_id: int
    """The selected link."""
    def __init__(self, *, data_link_id: int = ...) -> None: ...

class ReportHeartbeatPulse(Message):
    """A heartbeat, sent once a second by every component to its node manager and by node managers and communicators to their peers; also the answer to Query Heartbeat Pulse (code 0x4202)."""

    def __init__(self) -> None: ...

class SetComponentAuthority(Message):
    """Sets the authority code of the receiving component (code 0x0001)."""

    authority_code: int
    """The new authority, 0 (lowest) to 255."""
    def __init__(self, *, authority_code: int = ...) -> None: ...

class Shutdown(Message):
    """Commands the receiving component to the Shutdown state (code 0x0002)."""

    def __init__(self) -> None: ...

class Standby(Message):
    """Commands the receiving component from Ready to Standby (code 0x0003)."""

    def __init__(self) -> None: ...

class Resume(Message):
    """Commands the receiving component from Standby back to Ready (code 0x0004)."""

    def __init__(self) -> None: ...

class Reset(Message):
    """Commands the receiving component back to Initialize (code 0x0005)."""

    def __init__(self) -> None: ...

class SetEmergency(Message):
    """Commands the receiving component to the Emergency state. Honoured from any sender, whatever the control state, because safety requires it (code 0x0006)."""

    emergency_code: Record
    """Emergency bits; bit 0 enters Emergency."""
    def __init__(self, *, emergency_code: _RecordIn = ...) -> None: ...

class ClearEmergency(Message):
    """Clears the Emergency state; the component returns to Standby (code 0x0007)."""

    emergency_code: Record
    """Emergency bits; bit 0 clears Emergency."""
    def __init__(self, *, emergency_code: _RecordIn = ...) -> None: ...

class CreateServiceConnection(Message):
    """Asks a component to send a report periodically (a service connection). The last field is the presence vector wanted in the streamed report, not a presence vector of this message (code 0x0008)."""

    service_connection_command_code: int
    """Code of the report to stream."""
    requested_periodic_update_rate: float
    """Unit: Hz. Requested rate."""
    presence_vector: int
    """Presence vector of the streamed report."""
    def __init__(self, *, service_connection_command_code: int = ..., requested_periodic_update_rate: float = ..., presence_vector: int = ...) -> None: ...

class ConfirmServiceConnection(Message):
    """Answers Create Service Connection (code 0x0009)."""

    service_connection_command_code: int
    """Code of the streamed report."""
    instance_id: int
    """Identifies this connection among several from the same requester for the same code."""
    confirmed_periodic_update_rate: float
    """Unit: Hz. Rate the provider will send at."""
    response_code: Union[Literal["Successful", "NodeNotCapable", "ComponentNotCapable", "InsufficientAuthority", "ConnectionRefused", "InvalidParameter", "CommandNotSupported"], Record]
    """Outcome of the request."""
    def __init__(self, *, service_connection_command_code: int = ..., instance_id: int = ..., confirmed_periodic_update_rate: float = ..., response_code: Union[Literal["Successful", "NodeNotCapable", "ComponentNotCapable", "InsufficientAuthority", "ConnectionRefused", "InvalidParameter", "CommandNotSupported"], _RecordIn] = ...) -> None: ...

class ActivateServiceConnection(Message):
    """Resumes a suspended service connection (code 0x000A)."""

    service_connection_command_code: int
    """Code of the streamed report."""
    instance_id: int
    """Connection instance from Confirm Service Connection."""
    def __init__(self, *, service_connection_command_code: int = ..., instance_id: int = ...) -> None: ...

class SuspendServiceConnection(Message):
    """Pauses a service connection (code 0x000B)."""

    service_connection_command_code: int
    """Code of the streamed report."""
    instance_id: int
    """Connection instance from Confirm Service Connection."""
    def __init__(self, *, service_connection_command_code: int = ..., instance_id: int = ...) -> None: ...

class TerminateServiceConnection(Message):
    """Ends a service connection; either side may send it (code 0x000C)."""

    service_connection_command_code: int
    """Code of the streamed report."""
    instance_id: int
    """Connection instance from Confirm Service Connection."""
    def __init__(self, *, service_connection_command_code: int = ..., instance_id: int = ...) -> None: ...

class RequestComponentControl(Message):
    """Asks for exclusive control of the receiving component (code 0x000D)."""

    authority_code: int
    """Authority of the requester; a higher authority takes control from a lower one."""
    def __init__(self, *, authority_code: int = ...) -> None: ...

class ReleaseComponentControl(Message):
    """Gives up control of the receiving component (code 0x000E)."""

    def __init__(self) -> None: ...

class ConfirmComponentControl(Message):
    """Answers Request Component Control (code 0x000F)."""

    response_code: Union[Literal["ControlAccepted", "NotAvailable", "InsufficientAuthority"], Record]
    """Outcome of the request."""
    def __init__(self, *, response_code: Union[Literal["ControlAccepted", "NotAvailable", "InsufficientAuthority"], _RecordIn] = ...) -> None: ...

class RejectComponentControl(Message):
    """Tells the (former) controller that it no longer has control (code 0x0010)."""

    def __init__(self) -> None: ...

class SetTime(Message):
    """Sets the clock of the receiving component (code 0x0011)."""

    time_stamp: Optional[Record]
    """Optional: presence bit 0. Time of day."""
    date_stamp: Optional[Record]
    """Optional: presence bit 1. Date."""
    def __init__(self, *, time_stamp: _RecordIn = ..., date_stamp: _RecordIn = ...) -> None: ...

class QueryComponentAuthority(Message):
    """Asks for the authority code of the receiving component (code 0x2001)."""

    def __init__(self) -> None: ...

class QueryComponentStatus(Message):
    """Asks for the state of the receiving component (code 0x2002)."""

    def __init__(self) -> None: ...

class QueryComponentControl(Message):
    """Asks which component controls the receiving component (code 0x200D)."""

    def __init__(self) -> None: ...

class QueryTime(Message):
    """Asks for the clock of the receiving component (code 0x2011)."""

    presence_vector: int
    """Fields wanted in Report Time: bit 0 time stamp, bit 1 date stamp."""
    def __init__(self, *, presence_vector: int = ...) -> None: ...

class ReportComponentAuthority(Message):
    """The authority code of the sending component (code 0x4001)."""

    authority_code: int
    """Authority, 0 (lowest) to 255."""
    def __init__(self, *, authority_code: int = ...) -> None: ...

class ReportComponentStatus(Message):
    """The state of the sending component (code 0x4002)."""

    primary_status_code: Union[Literal["Initialize", "Ready", "Standby", "Shutdown", "Failure", "Emergency"], Record]
    """Core state."""
    secondary_status_code: int
    """Component-specific status (OpenJAUS sends 0)."""
    def __init__(self, *, primary_status_code: Union[Literal["Initialize", "Ready", "Standby", "Shutdown", "Failure", "Emergency"], _RecordIn] = ..., secondary_status_code: int = ...) -> None: ...

class ReportComponentControl(Message):
    """The component controlling the sender, all zero when none. The address bytes are in subsystem, node, component, instance order (reversed relative to the header) (code 0x400D)."""

    subsystem_id: int
    """Controller subsystem."""
    node_id: int
    """Controller node."""
    component_id: int
    """Controller component."""
    instance_id: int
    """Controller instance."""
    authority_code: int
    """Authority the controller requested control with."""
    def __init__(self, *, subsystem_id: int = ..., node_id: int = ..., component_id: int = ..., instance_id: int = ..., authority_code: int = ...) -> None: ...

class ReportTime(Message):
    """The clock of the sending component (code 0x4011)."""

    time_stamp: Optional[Record]
    """Optional: presence bit 0. Time of day."""
    date_stamp: Optional[Record]
    """Optional: presence bit 1. Date."""
    def __init__(self, *, time_stamp: _RecordIn = ..., date_stamp: _RecordIn = ...) -> None: ...

class ReportRefusal(Message):
    """Why a message was refused, sent by this SDK's component runtime and node access policy to a sender that asked for an acknowledgement, just before the NAK (the JAUS header's NAK carries no reason). Not part of RA 3.3: an experimental message in the range the SDK keeps for its own (0xDF00-0xDFFF); other implementations ignore it (code 0xDF01)."""

    refused_code: int
    """Command code of the refused message."""
    reason: Union[Literal["NotController", "WrongState", "Unsupported", "Invalid", "OutOfRange", "Policy", "ForeignClearEmergency", "Undecodable"], Record]
    """Why it was refused."""
    text: str
    """The reason in words, naming the field, value and limit where there are some (at most 255 bytes)."""
    def __init__(self, *, refused_code: int = ..., reason: Union[Literal["NotController", "WrongState", "Unsupported", "Invalid", "OutOfRange", "Policy", "ForeignClearEmergency", "Undecodable"], _RecordIn] = ..., text: str = ...) -> None: ...

class QueryIdentification(Message):
    """Asks for the name of the system, subsystem, node or component (code 0x2B00)."""

    query_field: Union[Literal["System", "Subsystem", "Node", "Component"], Record]
    """Which identification is wanted."""
    def __init__(self, *, query_field: Union[Literal["System", "Subsystem", "Node", "Component"], _RecordIn] = ...) -> None: ...

class QueryConfiguration(Message):
    """Asks for the nodes and components of the subsystem or node (code 0x2B01)."""

    query_field: Union[Literal["System", "Subsystem", "Node", "Component"], Record]
    """Subsystem or node configuration."""
    def __init__(self, *, query_field: Union[Literal["System", "Subsystem", "Node", "Component"], _RecordIn] = ...) -> None: ...

class QuerySubsystemList(Message):
    """Asks for the subsystems of the system (nobody in OpenJAUS answers it) (code 0x2B02)."""

    def __init__(self) -> None: ...

class QueryServices(Message):
    """Asks for the services of the receiving component (code 0x2B03)."""

    def __init__(self) -> None: ...

class ReportIdentification(Message):
    """The name of the system, subsystem, node or component (code 0x4B00)."""

    query_type: Union[Literal["System", "Subsystem", "Node", "Component"], Record]
    """The identification being answered."""
    authority: int
    """Lowest authority needed to control the entity."""
    identification_type: int
    """Entity type (0 reserved; OpenJAUS sends 0)."""
    identification: str
    """Name of the entity."""
    def __init__(self, *, query_type: Union[Literal["System", "Subsystem", "Node", "Component"], _RecordIn] = ..., authority: int = ..., identification_type: int = ..., identification: str = ...) -> None: ...

class ReportConfiguration(Message):
    """The nodes and components of the sender's subsystem, or of its node (one node entry). A subsystem report with no nodes means the subsystem is gone (code 0x4B01)."""

    nodes: List[Record]
    """The nodes."""
    def __init__(self, *, nodes: List[_RecordIn] = ...) -> None: ...

class ReportSubsystemList(Message):
    """The subsystems of the system (code 0x4B02)."""

    subsystems: List[Record]
    """The subsystems."""
    def __init__(self, *, subsystems: List[_RecordIn] = ...) -> None: ...

class ReportServices(Message):
    """The services of the sending component and the messages of each (code 0x4B03)."""

    services: List[Record]
    """The services."""
    def __init__(self, *, services: List[_RecordIn] = ...) -> None: ...

class SetCameraPose(Message):
    """Commands a camera's pose: for each linear and angular axis, a position or a rate (chosen by the mode bit of that axis), in percent of the axis's range (code 0x0801)."""

    camera_id: int
    """Camera to move."""
    mode: Record
    """Position or rate mode of each axis."""
    x_linear_position_or_rate: Optional[float]
    """Unit: %. Optional: presence bit 0. X linear position or rate."""
    y_linear_position_or_rate: Optional[float]
    """Unit: %. Optional: presence bit 1. Y linear position or rate."""
    z_linear_position_or_rate: Optional[float]
    """Unit: %. Optional: presence bit 2. Z linear position or rate."""
    x_angular_position_or_rate: Optional[float]
    """Unit: %. Optional: presence bit 3. X angular position or rate."""
    y_angular_position_or_rate: Optional[float]
    """Unit: %. Optional: presence bit 4. Y angular position or rate."""
    z_angular_position_or_rate: Optional[float]
    """Unit: %. Optional: presence bit 5. Z angular position or rate."""
    def __init__(self, *, camera_id: int = ..., mode: _RecordIn = ..., x_linear_position_or_rate: float = ..., y_linear_position_or_rate: float = ..., z_linear_position_or_rate: float = ..., x_angular_position_or_rate: float = ..., y_angular_position_or_rate: float = ..., z_angular_position_or_rate: float = ...) -> None: ...

class SelectCamera(Message):
    """Selects the camera whose images the visual sensor sends (code 0x0802)."""

    camera_id: int
    """Camera to select."""
    def __init__(self, *, camera_id: int = ...) -> None: ...

class SetCameraCapabilities(Message):
    """Sets a camera's field of view, resolution, focus, iris, gain, frame rate, shutter speed and image and audio controls (code 0x0805)."""

    camera_id: int
    """Camera to configure."""
    horizontal_fov: Optional[float]
    """Unit: rad. Optional: presence bit 0. Horizontal field of view."""
    vertical_fov: Optional[float]
    """Unit: rad. Optional: presence bit 1. Vertical field of view."""
    horizontal_resolution: Optional[int]
    """Optional: presence bit 2. Horizontal resolution (raw value, pixels or lines)."""
    vertical_resolution: Optional[int]
    """Optional: presence bit 3. Vertical resolution (raw value, pixels or lines)."""
    focus: Optional[float]
    """Unit: %. Optional: presence bit 4. Focus."""
    iris: Optional[float]
    """Unit: %. Optional: presence bit 5. Iris opening."""
    gain: Optional[float]
    """Unit: %. Optional: presence bit 6. Gain."""
    frame_rate: Optional[int]
    """Optional: presence bit 7. Frame rate (raw value, not scaled)."""
    shutter_speed: Optional[int]
    """Optional: presence bit 8. Shutter speed (raw value, not scaled)."""
    image_control: Optional[Record]
    """Optional: presence bit 9. Image-control features to turn on."""
    audio_control: Optional[Record]
    """Optional: presence bit 10. Audio-control features to turn on."""
    def __init__(self, *, camera_id: int = ..., horizontal_fov: float = ..., vertical_fov: float = ..., horizontal_resolution: int = ..., vertical_resolution: int = ..., focus: float = ..., iris: float = ..., gain: float = ..., frame_rate: int = ..., shutter_speed: int = ..., image_control: _RecordIn = ..., audio_control: _RecordIn = ...) -> None: ...

class SetCameraFormatOptions(Message):
    """Sets the audio and image format a camera sends, and a format-specific option (code 0x0806)."""

    camera_id: int
    """Camera to configure."""
    audio_format: Optional[Union[Literal["Unused", "RawAudio", "Pcm", "Au", "Wav", "Mid", "Mp3", "Mp2", "Asf"], Record]]
    """Optional: presence bit 0. Audio format."""
    image_format: Optional[Union[Literal["Unused", "Mpeg2", "Mpeg4", "Mjpeg", "Ntsc", "Pal", "Tiff", "Jpeg", "Gif", "H263", "H264", "Png", "Bmp", "RawImage", "Ppm", "Pgm", "Pnm"], Record]]
    """Optional: presence bit 1. Image format."""
    format_option: Optional[int]
    """Optional: presence bit 2. Format-specific option (raw value)."""
    def __init__(self, *, camera_id: int = ..., audio_format: Union[Literal["Unused", "RawAudio", "Pcm", "Au", "Wav", "Mid", "Mp3", "Mp2", "Asf"], _RecordIn] = ..., image_format: Union[Literal["Unused", "Mpeg2", "Mpeg4", "Mjpeg", "Ntsc", "Pal", "Tiff", "Jpeg", "Gif", "H263", "H264", "Png", "Bmp", "RawImage", "Ppm", "Pgm", "Pnm"], _RecordIn] = ..., format_option: int = ...) -> None: ...

class QueryCameraPose(Message):
    """Asks for the pose of a camera (code 0x2800)."""

    presence_vector: int
    """Fields wanted in Report Camera Pose."""
    camera_id: int
    """Camera asked about."""
    def __init__(self, *, presence_vector: int = ..., camera_id: int = ...) -> None: ...

class QueryCameraCount(Message):
    """Asks how many cameras the visual sensor has (code 0x2801)."""

    def __init__(self) -> None: ...

class QueryRelativeObjectPosition(Message):
    """Asks for the position of an object relative to the range sensor (code 0x2802)."""

    presence_vector: int
    """Fields wanted in Report Relative Object Position."""
    def __init__(self, *, presence_vector: int = ...) -> None: ...

class QuerySelectedCamera(Message):
    """Asks which camera is selected (code 0x2804)."""

    def __init__(self) -> None: ...

class QueryCameraCapabilities(Message):
    """Asks for the capabilities of a camera (code 0x2805)."""

    presence_vector: int
    """Fields wanted in Report Camera Capabilities."""
    camera_id: int
    """Camera asked about."""
    def __init__(self, *, presence_vector: int = ..., camera_id: int = ...) -> None: ...

class QueryCameraFormatOptions(Message):
    """Asks for the format options of a camera (code 0x2806)."""

    presence_vector: int
    """Fields wanted in Report Camera Format Options."""
    camera_id: int
    """Camera asked about."""
    def __init__(self, *, presence_vector: int = ..., camera_id: int = ...) -> None: ...

class QueryImage(Message):
    """Asks for an image from the selected camera (code 0x2807)."""

    def __init__(self) -> None: ...

class QueryMap(Message):
    """Asks for a map (OpenJAUS experimental; not part of RA 3.3) (code 0x28F1)."""

    map_id: int
    """Map asked about."""
    def __init__(self, *, map_id: int = ...) -> None: ...

class ReportCameraPose(Message):
    """A camera's name and pose relative to the platform: the position of its origin and the direction cosines of its X and Z axes (code 0x4800)."""

    camera_id: int
    """Camera reported on."""
    camera_name: Optional[str]
    """Optional: presence bit 0. Camera name, NUL-padded to 15 bytes."""
    x_camera_origin: Optional[float]
    """Unit: m. Optional: presence bit 1. X coordinate of the camera origin."""
    y_camera_origin: Optional[float]
    """Unit: m. Optional: presence bit 2. Y coordinate of the camera origin."""
    z_camera_origin: Optional[float]
    """Unit: m. Optional: presence bit 3. Z coordinate of the camera origin."""
    x_camera_axis_direction_cosine_x: Optional[float]
    """Optional: presence bit 4. X component of the direction cosine of the camera's X axis."""
    x_camera_axis_direction_cosine_y: Optional[float]
    """Optional: presence bit 5. Y component of the direction cosine of the camera's X axis."""
    x_camera_axis_direction_cosine_z: Optional[float]
    """Optional: presence bit 6. Z component of the direction cosine of the camera's X axis."""
    z_camera_axis_direction_cosine_x: Optional[float]
    """Optional: presence bit 7. X component of the direction cosine of the camera's Z axis."""
    z_camera_axis_direction_cosine_y: Optional[float]
    """Optional: presence bit 8. Y component of the direction cosine of the camera's Z axis."""
    z_camera_axis_direction_cosine_z: Optional[float]
    """Optional: presence bit 9. Z component of the direction cosine of the camera's Z axis."""
    def __init__(self, *, camera_id: int = ..., camera_name: str = ..., x_camera_origin: float = ..., y_camera_origin: float = ..., z_camera_origin: float = ..., x_camera_axis_direction_cosine_x: float = ..., x_camera_axis_direction_cosine_y: float = ..., x_camera_axis_direction_cosine_z: float = ..., z_camera_axis_direction_cosine_x: float = ..., z_camera_axis_direction_cosine_y: float = ..., z_camera_axis_direction_cosine_z: float = ...) -> None: ...

class ReportCameraCount(Message):
    """How many cameras the visual sensor has (code 0x4801)."""

    camera_count: int
    """Number of cameras."""
    def __init__(self, *, camera_count: int = ...) -> None: ...

class ReportRelativeObjectPosition(Message):
    """The position of an object relative to the range sensor (range, bearing and inclination, with their errors), the confidence of the detection and the object's identifier, at a given time (code 0x4802)."""

    time_stamp: Record
    """Time of the measurement (always present)."""
    range: Optional[float]
    """Unit: m. Optional: presence bit 0. Range to the object."""
    range_error: Optional[float]
    """Unit: m. Optional: presence bit 1. Error of the range."""
    bearing: Optional[float]
    """Unit: rad. Optional: presence bit 2. Bearing of the object."""
    bearing_error: Optional[float]
    """Unit: rad. Optional: presence bit 3. Error of the bearing."""
    inclination: Optional[float]
    """Unit: rad. Optional: presence bit 4. Inclination of the object."""
    inclination_error: Optional[float]
    """Unit: rad. Optional: presence bit 5. Error of the inclination."""
    confidence_and_object_id: Optional[bool]
    """Optional: presence bit 6. Whether the confidence and the object id are sent (one bit for both, as OpenJAUS does)."""
    confidence: Optional[int]
    """Confidence of the detection (raw value)."""
    object_id: Optional[int]
    """Identifier of the object."""
    def __init__(self, *, time_stamp: _RecordIn = ..., range: float = ..., range_error: float = ..., bearing: float = ..., bearing_error: float = ..., inclination: float = ..., inclination_error: float = ..., confidence_and_object_id: bool = ..., confidence: int = ..., object_id: int = ...) -> None: ...

class ReportSelectedCamera(Message):
    """Which camera is selected (code 0x4804)."""

    camera_id: int
    """Selected camera."""
    def __init__(self, *, camera_id: int = ...) -> None: ...

class ReportCameraCapabilities(Message):
    """A camera's description and the ranges of its field of view, resolution, frame rate and shutter speed, and which image and audio controls it offers (code 0x4805)."""

    camera_id: int
    """Camera reported on."""
    camera_description: Optional[str]
    """Optional: presence bit 0. Camera description, NUL-padded to 50 bytes."""
    max_horizontal_fov: Optional[float]
    """Unit: rad. Optional: presence bit 1. Maximum horizontal field of view."""
    min_horizontal_fov: Optional[float]
    """Unit: rad. Optional: presence bit 2. Minimum horizontal field of view."""
    max_vertical_fov: Optional[float]
    """Unit: rad. Optional: presence bit 3. Maximum vertical field of view."""
    min_vertical_fov: Optional[float]
    """Unit: rad. Optional: presence bit 4. Minimum vertical field of view."""
    max_horizontal_resolution: Optional[int]
    """Optional: presence bit 5. Maximum horizontal resolution (raw value)."""
    min_horizontal_resolution: Optional[int]
    """Optional: presence bit 6. Minimum horizontal resolution (raw value)."""
    max_vertical_resolution: Optional[int]
    """Optional: presence bit 7. Maximum vertical resolution (raw value)."""
    min_vertical_resolution: Optional[int]
    """Optional: presence bit 8. Minimum vertical resolution (raw value)."""
    max_frame_rate: Optional[int]
    """Optional: presence bit 9. Maximum frame rate (raw value)."""
    min_frame_rate: Optional[int]
    """Optional: presence bit 10. Minimum frame rate (raw value)."""
    max_shutter_speed: Optional[int]
    """Optional: presence bit 11. Maximum shutter speed (raw value)."""
    min_shutter_speed: Optional[int]
    """Optional: presence bit 12. Minimum shutter speed (raw value)."""
    image_control: Optional[Record]
    """Optional: presence bit 13. Image-control features the camera offers."""
    audio_control: Optional[Record]
    """Optional: presence bit 14. Audio-control features the camera offers."""
    def __init__(self, *, camera_id: int = ..., camera_description: str = ..., max_horizontal_fov: float = ..., min_horizontal_fov: float = ..., max_vertical_fov: float = ..., min_vertical_fov: float = ..., max_horizontal_resolution: int = ..., min_horizontal_resolution: int = ..., max_vertical_resolution: int = ..., min_vertical_resolution: int = ..., max_frame_rate: int = ..., min_frame_rate: int = ..., max_shutter_speed: int = ..., min_shutter_speed: int = ..., image_control: _RecordIn = ..., audio_control: _RecordIn = ...) -> None: ...

class ReportCameraFormatOptions(Message):
    """The audio formats (up to two) and image formats (up to four) a camera offers, and a format-specific option (code 0x4806)."""

    camera_id: int
    """Camera reported on."""
    audio_format_1: Optional[Union[Literal["Unused", "RawAudio", "Pcm", "Au", "Wav", "Mid", "Mp3", "Mp2", "Asf"], Record]]
    """Optional: presence bit 0. First audio format offered."""
    audio_format_2: Optional[Union[Literal["Unused", "RawAudio", "Pcm", "Au", "Wav", "Mid", "Mp3", "Mp2", "Asf"], Record]]
    """Optional: presence bit 1. Second audio format offered."""
    image_format_1: Optional[Union[Literal["Unused", "Mpeg2", "Mpeg4", "Mjpeg", "Ntsc", "Pal", "Tiff", "Jpeg", "Gif", "H263", "H264", "Png", "Bmp", "RawImage", "Ppm", "Pgm", "Pnm"], Record]]
    """Optional: presence bit 2. First image format offered."""
    image_format_2: Optional[Union[Literal["Unused", "Mpeg2", "Mpeg4", "Mjpeg", "Ntsc", "Pal", "Tiff", "Jpeg", "Gif", "H263", "H264", "Png", "Bmp", "RawImage", "Ppm", "Pgm", "Pnm"], Record]]
    """Optional: presence bit 3. Second image format offered."""
    image_format_3: Optional[Union[Literal["Unused", "Mpeg2", "Mpeg4", "Mjpeg", "Ntsc", "Pal", "Tiff", "Jpeg", "Gif", "H263", "H264", "Png", "Bmp", "RawImage", "Ppm", "Pgm", "Pnm"], Record]]
    """Optional: presence bit 4. Third image format offered."""
    image_format_4: Optional[Union[Literal["Unused", "Mpeg2", "Mpeg4", "Mjpeg", "Ntsc", "Pal", "Tiff", "Jpeg", "Gif", "H263", "H264", "Png", "Bmp", "RawImage", "Ppm", "Pgm", "Pnm"], Record]]
    """Optional: presence bit 5. Fourth image format offered."""
    format_option: Optional[int]
    """Optional: presence bit 6. Format-specific option (raw value)."""
    def __init__(self, *, camera_id: int = ..., audio_format_1: Union[Literal["Unused", "RawAudio", "Pcm", "Au", "Wav", "Mid", "Mp3", "Mp2", "Asf"], _RecordIn] = ..., audio_format_2: Union[Literal["Unused", "RawAudio", "Pcm", "Au", "Wav", "Mid", "Mp3", "Mp2", "Asf"], _RecordIn] = ..., image_format_1: Union[Literal["Unused", "Mpeg2", "Mpeg4", "Mjpeg", "Ntsc", "Pal", "Tiff", "Jpeg", "Gif", "H263", "H264", "Png", "Bmp", "RawImage", "Ppm", "Pgm", "Pnm"], _RecordIn] = ..., image_format_2: Union[Literal["Unused", "Mpeg2", "Mpeg4", "Mjpeg", "Ntsc", "Pal", "Tiff", "Jpeg", "Gif", "H263", "H264", "Png", "Bmp", "RawImage", "Ppm", "Pgm", "Pnm"], _RecordIn] = ..., image_format_3: Union[Literal["Unused", "Mpeg2", "Mpeg4", "Mjpeg", "Ntsc", "Pal", "Tiff", "Jpeg", "Gif", "H263", "H264", "Png", "Bmp", "RawImage", "Ppm", "Pgm", "Pnm"], _RecordIn] = ..., image_format_4: Union[Literal["Unused", "Mpeg2", "Mpeg4", "Mjpeg", "Ntsc", "Pal", "Tiff", "Jpeg", "Gif", "H263", "H264", "Png", "Bmp", "RawImage", "Ppm", "Pgm", "Pnm"], _RecordIn] = ..., format_option: int = ...) -> None: ...

class ReportImage(Message):
    """An image from a camera; the image data fill the rest of the body (code 0x4807)."""

    camera_id: int
    """Camera the image is from."""
    video_format: Union[Literal["Unused", "Mpeg2", "Mpeg4", "Mjpeg", "Ntsc", "Pal", "Tiff", "Jpeg", "Gif", "H263", "H264", "Png", "Bmp", "RawImage", "Ppm", "Pgm", "Pnm"], Record]
    """Format of the image data."""
    data: str
    """The image data, in the given format."""
    def __init__(self, *, camera_id: int = ..., video_format: Union[Literal["Unused", "Mpeg2", "Mpeg4", "Mjpeg", "Ntsc", "Pal", "Tiff", "Jpeg", "Gif", "H263", "H264", "Png", "Bmp", "RawImage", "Ppm", "Pgm", "Pnm"], _RecordIn] = ..., data: str = ...) -> None: ...

class ReportMap(Message):
    """One block of rows of a grid map (OpenJAUS experimental; not part of RA 3.3). The map data hold width × block height × depth bytes (OpenJAUS writes exactly that many): block-height rows of width cells of depth bytes each (code 0x48F1)."""

    map_id: int
    """Map reported on."""
    map_center_x: float
    """X coordinate of the map centre (unit not documented by OpenJAUS; presumably metres)."""
    map_center_y: float
    """Y coordinate of the map centre (unit not documented by OpenJAUS; presumably metres)."""
    width: int
    """Width of the map, in cells."""
    height: int
    """Height of the map, in cells."""
    depth: int
    """Bytes per cell."""
    block_index: int
    """Index of this block of rows within the map."""
    block_height: int
    """Rows per block."""
    cell_width_cm: int
    """Unit: cm. Width of a cell."""
    map_data: str
    """The cells of this block, row by row (width × block height × depth bytes)."""
    def __init__(self, *, map_id: int = ..., map_center_x: float = ..., map_center_y: float = ..., width: int = ..., height: int = ..., depth: int = ..., block_index: int = ..., block_height: int = ..., cell_width_cm: int = ..., map_data: str = ...) -> None: ...

class CreateEvent(Message):
    """Asks a component to send a report as an event. The provider answers with Confirm Event Request or Reject Event Request and then sends Event messages (code 0x01F0)."""

    request_id: int
    """Chosen by the requester; echoed in the confirm or reject."""
    report_message_code: int
    """Code of the report the event sends."""
    event_type: Union[Literal["Periodic", "EveryChange", "FirstChange", "FirstChangeInAndOutOfBoundary", "PeriodicWithoutReplacement", "OneTime"], Record]
    """When the event fires."""
    event_boundary: Optional[Union[Literal["Equal", "NotEqual", "InsideInclusive", "InsideExclusive", "OutsideInclusive", "OutsideExclusive", "GreaterThanOrEqual", "GreaterThan", "LessThanOrEqual", "LessThan"], Record]]
    """Optional: presence bit 0. How the tested field is compared with the limits."""
    limit_data_field: Optional[int]
    """Optional: presence bit 1. Index of the report field that is tested."""
    lower_limit: Optional[Union[str, Record]]
    """Optional: presence bit 2. Lower limit."""
    upper_limit: Optional[Union[str, Record]]
    """Optional: presence bit 3. Upper limit."""
    state_limit: Optional[Union[str, Record]]
    """Optional: presence bit 4. Value for the equal and not-equal boundaries."""
    requested_minimum_rate: Optional[float]
    """Unit: Hz. Optional: presence bit 5. Lowest acceptable periodic rate."""
    requested_update_rate: Optional[float]
    """Unit: Hz. Optional: presence bit 6. Requested periodic rate."""
    query_message: Optional[str]
    """Optional: presence bit 7. Body (no header) of the query that produces the report; its code is the complement of the report code."""
    def __init__(self, *, request_id: int = ..., report_message_code: int = ..., event_type: Union[Literal["Periodic", "EveryChange", "FirstChange", "FirstChangeInAndOutOfBoundary", "PeriodicWithoutReplacement", "OneTime"], _RecordIn] = ..., event_boundary: Union[Literal["Equal", "NotEqual", "InsideInclusive", "InsideExclusive", "OutsideInclusive", "OutsideExclusive", "GreaterThanOrEqual", "GreaterThan", "LessThanOrEqual", "LessThan"], _RecordIn] = ..., limit_data_field: int = ..., lower_limit: Union[str, _RecordIn] = ..., upper_limit: Union[str, _RecordIn] = ..., state_limit: Union[str, _RecordIn] = ..., requested_minimum_rate: float = ..., requested_update_rate: float = ..., query_message: str = ...) -> None: ...

class UpdateEvent(Message):
    """Changes an existing event; the same as Create Event plus the event ID (code 0x01F1)."""

    request_id: int
    """Chosen by the requester; echoed in the confirm or reject."""
    report_message_code: int
    """Code of the report the event sends."""
    event_type: Union[Literal["Periodic", "EveryChange", "FirstChange", "FirstChangeInAndOutOfBoundary", "PeriodicWithoutReplacement", "OneTime"], Record]
    """When the event fires."""
    event_boundary: Optional[Union[Literal["Equal", "NotEqual", "InsideInclusive", "InsideExclusive", "OutsideInclusive", "OutsideExclusive", "GreaterThanOrEqual", "GreaterThan", "LessThanOrEqual", "LessThan"], Record]]
    """Optional: presence bit 0. How the tested field is compared with the limits."""
    limit_data_field: Optional[int]
    """Optional: presence bit 1. Index of the report field that is tested."""
    lower_limit: Optional[Union[str, Record]]
    """Optional: presence bit 2. Lower limit."""
    upper_limit: Optional[Union[str, Record]]
    """Optional: presence bit 3. Upper limit."""
    state_limit: Optional[Union[str, Record]]
    """Optional: presence bit 4. Value for the equal and not-equal boundaries."""
    requested_minimum_rate: Optional[float]
    """Unit: Hz. Optional: presence bit 5. Lowest acceptable periodic rate."""
    requested_update_rate: Optional[float]
    """Unit: Hz. Optional: presence bit 6. Requested periodic rate."""
    event_id: int
    """The event to change."""
    query_message: Optional[str]
    """Optional: presence bit 7. Body (no header) of the query that produces the report; its code is the complement of the report code."""
    def __init__(self, *, request_id: int = ..., report_message_code: int = ..., event_type: Union[Literal["Periodic", "EveryChange", "FirstChange", "FirstChangeInAndOutOfBoundary", "PeriodicWithoutReplacement", "OneTime"], _RecordIn] = ..., event_boundary: Union[Literal["Equal", "NotEqual", "InsideInclusive", "InsideExclusive", "OutsideInclusive", "OutsideExclusive", "GreaterThanOrEqual", "GreaterThan", "LessThanOrEqual", "LessThan"], _RecordIn] = ..., limit_data_field: int = ..., lower_limit: Union[str, _RecordIn] = ..., upper_limit: Union[str, _RecordIn] = ..., state_limit: Union[str, _RecordIn] = ..., requested_minimum_rate: float = ..., requested_update_rate: float = ..., event_id: int = ..., query_message: str = ...) -> None: ...

class CancelEvent(Message):
    """Ends an event. OpenJAUS matches the message code against the query code of the event (e.g. 0x2B01), not the report code, and sends no reply (code 0x01F2)."""

    request_id: int
    """Chosen by the requester."""
    message_code: Optional[int]
    """Optional: presence bit 0. Message code of the event."""
    event_id: Optional[int]
    """Optional: presence bit 1. The event to cancel."""
    def __init__(self, *, request_id: int = ..., message_code: int = ..., event_id: int = ...) -> None: ...

class ConfirmEventRequest(Message):
    """Accepts a Create, Update or Cancel Event request (code 0x01F3)."""

    request_id: int
    """Request ID of the request being answered."""
    message_code: int
    """Code of the report the event sends."""
    event_id: int
    """Event ID assigned by the provider."""
    confirmed_update_rate: Optional[float]
    """Unit: Hz. Optional: presence bit 0. Periodic rate the provider will send at."""
    response_code: Union[Literal["Successful", "PeriodicEventsNotSupported", "ChangeBasedEventsNotSupported", "ConnectionRefused", "InvalidEventSetup", "MessageNotSupported"], Record]
    """Outcome of the request."""
    def __init__(self, *, request_id: int = ..., message_code: int = ..., event_id: int = ..., confirmed_update_rate: float = ..., response_code: Union[Literal["Successful", "PeriodicEventsNotSupported", "ChangeBasedEventsNotSupported", "ConnectionRefused", "InvalidEventSetup", "MessageNotSupported"], _RecordIn] = ...) -> None: ...

class RejectEventRequest(Message):
    """Refuses a Create, Update or Cancel Event request (code 0x01F4)."""

    request_id: int
    """Request ID of the request being answered."""
    response_code: Union[Literal["Successful", "PeriodicEventsNotSupported", "ChangeBasedEventsNotSupported", "ConnectionRefused", "InvalidEventSetup", "MessageNotSupported"], Record]
    """Why the request was refused."""
    error_message: Optional[str]
    """Optional: presence bit 0. Human-readable reason."""
    def __init__(self, *, request_id: int = ..., response_code: Union[Literal["Successful", "PeriodicEventsNotSupported", "ChangeBasedEventsNotSupported", "ConnectionRefused", "InvalidEventSetup", "MessageNotSupported"], _RecordIn] = ..., error_message: str = ...) -> None: ...

class QueryEvents(Message):
    """Asks for the events a component has set up. The presence vector selects the filters; with no bits set every event is reported (code 0x21F0)."""

    message_code: Optional[int]
    """Optional: presence bit 0. Only events sending this report code."""
    event_type: Optional[Union[Literal["Periodic", "EveryChange", "FirstChange", "FirstChangeInAndOutOfBoundary", "PeriodicWithoutReplacement", "OneTime"], Record]]
    """Optional: presence bit 1. Only events of this type."""
    event_id: Optional[int]
    """Optional: presence bit 2. Only this event."""
    def __init__(self, *, message_code: int = ..., event_type: Union[Literal["Periodic", "EveryChange", "FirstChange", "FirstChangeInAndOutOfBoundary", "PeriodicWithoutReplacement", "OneTime"], _RecordIn] = ..., event_id: int = ...) -> None: ...

class ReportEvents(Message):
    """The events a component has set up, answering Query Events (code 0x41F0)."""

    events: List[Record]
    """The events."""
    def __init__(self, *, events: List[_RecordIn] = ...) -> None: ...

class Event(Message):
    """An event notification carrying a report. The report body is decoded with the decoder of report_message_code, using the Event's source and destination (code 0x41F1)."""

    event_id: int
    """Event ID from Confirm Event Request."""
    report_message_code: int
    """Code of the embedded report."""
    event_sequence_number: int
    """Occurrence counter of the event."""
    report_message: str
    """Body (no header) of the report."""
    def __init__(self, *, event_id: int = ..., report_message_code: int = ..., event_sequence_number: int = ..., report_message: str = ...) -> None: ...

class SetJointEfforts(Message):
    """Commands the effort of each joint of the manipulator, in percent of its maximum (code 0x0601)."""

    joint_effort: List[float]
    """Unit: %. Effort of each joint, first joint first."""
    def __init__(self, *, joint_effort: List[float] = ...) -> None: ...

class SetJointPositions(Message):
    """Commands the position of each joint of the manipulator (code 0x0602)."""

    joint_position: List[float]
    """Unit: rad. Position of each joint (metres for a prismatic joint), first joint first; limits ±8π."""
    def __init__(self, *, joint_position: List[float] = ...) -> None: ...

class SetJointVelocities(Message):
    """Commands the velocity of each joint of the manipulator (code 0x0603)."""

    joint_velocity: List[float]
    """Unit: rad/s. Velocity of each joint (m/s for a prismatic joint), first joint first; limits ±10π."""
    def __init__(self, *, joint_velocity: List[float] = ...) -> None: ...

class SetToolPoint(Message):
    """Sets the tool point, the point of the end effector that the end-effector drivers position, in the last link's coordinate system (code 0x0604)."""

    x: float
    """Unit: m. X coordinate of the tool point."""
    y: float
    """Unit: m. Y coordinate of the tool point."""
    z: float
    """Unit: m. Z coordinate of the tool point."""
    def __init__(self, *, x: float = ..., y: float = ..., z: float = ...) -> None: ...

class SetEndEffectorPose(Message):
    """Commands the position of the tool point and the orientation of the end effector, the orientation as a unit quaternion d + ai + bj + ck (sent d first) (code 0x0605)."""

    x: float
    """Unit: m. X coordinate of the tool point."""
    y: float
    """Unit: m. Y coordinate of the tool point."""
    z: float
    """Unit: m. Z coordinate of the tool point."""
    d: float
    """Quaternion scalar component d."""
    a: float
    """Quaternion component a (i)."""
    b: float
    """Quaternion component b (j)."""
    c: float
    """Quaternion component c (k)."""
    def __init__(self, *, x: float = ..., y: float = ..., z: float = ..., d: float = ..., a: float = ..., b: float = ..., c: float = ...) -> None: ...

class SetEndEffectorVelocityState(Message):
    """Commands the angular and linear velocity of the end effector (code 0x0606)."""

    coordinate_system: int
    """Coordinate system the velocities are expressed in (raw value; OpenJAUS does not interpret it)."""
    x_angular: float
    """Unit: rad/s. Angular velocity about X; limits ±20π."""
    y_angular: float
    """Unit: rad/s. Angular velocity about Y; limits ±20π."""
    z_angular: float
    """Unit: rad/s. Angular velocity about Z; limits ±20π."""
    x_linear: float
    """Unit: m/s. Linear velocity along X."""
    y_linear: float
    """Unit: m/s. Linear velocity along Y."""
    z_linear: float
    """Unit: m/s. Linear velocity along Z."""
    def __init__(self, *, coordinate_system: int = ..., x_angular: float = ..., y_angular: float = ..., z_angular: float = ..., x_linear: float = ..., y_linear: float = ..., z_linear: float = ...) -> None: ...

class SetEndEffectorPathMotion(Message):
    """Commands the end effector along a path given as a sequence of timed poses (code 0x0608)."""

    poses: List[Record]
    """The poses, in the order they are to be reached."""
    def __init__(self, *, poses: List[_RecordIn] = ...) -> None: ...

class QueryJointEfforts(Message):
    """Asks for the current effort of each joint (code 0x2601)."""

    def __init__(self) -> None: ...

class QueryJointPositions(Message):
    """Asks for the current position of each joint (code 0x2602)."""

    def __init__(self) -> None: ...

class QueryJointVelocities(Message):
    """Asks for the current velocity of each joint (code 0x2603)."""

    def __init__(self) -> None: ...

class QueryToolPoint(Message):
    """Asks for the current tool point (code 0x2604)."""

    def __init__(self) -> None: ...

class QueryJointForceTorques(Message):
    """Asks for the current force or torque on each joint (code 0x2605)."""

    def __init__(self) -> None: ...

class ReportJointEfforts(Message):
    """The current effort of each joint of the manipulator, in percent of its maximum (code 0x4601)."""

    joint_effort: List[float]
    """Unit: %. Effort of each joint, first joint first."""
    def __init__(self, *, joint_effort: List[float] = ...) -> None: ...

class ReportJointPositions(Message):
    """The current position of each joint of the manipulator (code 0x4602)."""

    joint_position: List[float]
    """Unit: rad. Position of each joint (metres for a prismatic joint), first joint first; limits ±8π."""
    def __init__(self, *, joint_position: List[float] = ...) -> None: ...

class ReportJointVelocities(Message):
    """The current velocity of each joint of the manipulator (code 0x4603)."""

    joint_velocity: List[float]
    """Unit: rad/s. Velocity of each joint (m/s for a prismatic joint), first joint first; limits ±10π."""
    def __init__(self, *, joint_velocity: List[float] = ...) -> None: ...

class ReportToolPoint(Message):
    """The current tool point, in the last link's coordinate system (code 0x4604)."""

    x: float
    """Unit: m. X coordinate of the tool point."""
    y: float
    """Unit: m. Y coordinate of the tool point."""
    z: float
    """Unit: m. Z coordinate of the tool point."""
    def __init__(self, *, x: float = ..., y: float = ..., z: float = ...) -> None: ...

class ReportJointForceTorques(Message):
    """The current force (prismatic joint, N) or torque (revolute joint, N·m) on each joint (code 0x4605)."""

    joint_force_torque: List[float]
    """Force (N) or torque (N·m) on each joint, first joint first."""
    def __init__(self, *, joint_force_torque: List[float] = ...) -> None: ...

class SetJointMotion(Message):
    """Commands the manipulator through a sequence of joint-space poses, each with the time to reach it and per-joint velocity, acceleration and deceleration limits (code 0x0607)."""

    num_joints: int
    """Number of joints; every pose lists this many."""
    num_poses: int
    """Number of poses (computed from `poses` on encode)."""
    poses: List[Record]
    """The poses, in order."""
    def __init__(self, *, num_joints: int = ..., num_poses: int = ..., poses: List[_RecordIn] = ...) -> None: ...

class QueryManipulatorSpecifications(Message):
    """Asks for the manipulator's kinematic specification (code 0x2600)."""

    def __init__(self) -> None: ...

class ReportManipulatorSpecifications(Message):
    """The manipulator's kinematic chain: the joint count, the first joint, the base coordinate system, then each further joint with the link leading to it. A manipulator with no joints sends the count only. OpenJAUS lists the first joint last in its data structure; the wire order is the one here (code 0x4600)."""

    num_joints: int
    """Number of joints."""
    first_joint: Optional[Union[str, Record]]
    """The joint at the base."""
    coordinate_system: Optional[Record]
    """Base frame in the vehicle frame."""
    linked_joints: List[Union[str, Record]]
    """The other joints, each after its link."""
    def __init__(self, *, num_joints: int = ..., first_joint: Union[str, _RecordIn] = ..., coordinate_system: _RecordIn = ..., linked_joints: List[Union[str, _RecordIn]] = ...) -> None: ...

class SetPayloadDataElement(Message):
    """Sets data elements of a payload's command interfaces. Each element is a u8 interface index (1-based, into the command interfaces) followed by a value whose type is that interface's type code; `jaus::payload` reads and writes them (code 0x0D01)."""

    element_count: int
    """Number of elements."""
    elements: str
    """The elements: index, then the value, for each."""
    def __init__(self, *, element_count: int = ..., elements: str = ...) -> None: ...

class QueryPayloadInterface(Message):
    """Asks a payload for the definition of its interface (its data elements) (code 0x2D00)."""

    def __init__(self) -> None: ...

class QueryPayloadDataElement(Message):
    """Asks a payload for the current values of some of its information interfaces (code 0x2D01)."""

    indexes: List[int]
    """Interface indexes of the data elements wanted."""
    def __init__(self, *, indexes: List[int] = ...) -> None: ...

class ReportPayloadDataElement(Message):
    """Current values of data elements of a payload's information interfaces: each a u8 interface index (1-based, into the information interfaces) followed by a value whose type is that interface's type code; `jaus::payload` reads and writes them (code 0x4D01)."""

    element_count: int
    """Number of elements."""
    elements: str
    """The elements: index, then the value, for each."""
    def __init__(self, *, element_count: int = ..., elements: str = ...) -> None: ...

class ReportPayloadInterface(Message):
    """A payload's interface: its command interfaces (settable data elements) and information interfaces (reported data elements), with their types, ranges and HMI recommendations. Their order gives the 1-based indexes that data element messages use (code 0x4D00)."""

    has_hmi_recommendation: Optional[bool]
    """Optional: presence bit 0. Interfaces carry an HMI recommendation."""
    has_hmi_x: Optional[bool]
    """Optional: presence bit 1. Interfaces carry a recommended HMI X position."""
    has_hmi_y: Optional[bool]
    """Optional: presence bit 2. Interfaces carry a recommended HMI Y position."""
    has_hmi_width: Optional[bool]
    """Optional: presence bit 3. Interfaces carry a recommended HMI width."""
    has_hmi_height: Optional[bool]
    """Optional: presence bit 4. Interfaces carry a recommended HMI height."""
    command_interface_count: int
    """Number of command interfaces (computed on encode)."""
    information_interface_count: int
    """Number of information interfaces (computed on encode)."""
    command_interfaces: List[Record]
    """Command interfaces, index 1 first."""
    information_interfaces: List[Record]
    """Information interfaces, index 1 first."""
    def __init__(self, *, has_hmi_recommendation: bool = ..., has_hmi_x: bool = ..., has_hmi_y: bool = ..., has_hmi_width: bool = ..., has_hmi_height: bool = ..., command_interface_count: int = ..., information_interface_count: int = ..., command_interfaces: List[_RecordIn] = ..., information_interfaces: List[_RecordIn] = ...) -> None: ...

class RunMission(Message):
    """Starts a spooled mission (code 0x0E01)."""

    mission_id: int
    """The mission to run."""
    def __init__(self, *, mission_id: int = ...) -> None: ...

class AbortMission(Message):
    """Aborts a mission, or one task of it (code 0x0E02)."""

    mission_id: int
    """The mission."""
    task_id: int
    """The task to abort; 0 aborts the whole mission."""
    def __init__(self, *, mission_id: int = ..., task_id: int = ...) -> None: ...

class PauseMission(Message):
    """Pauses a mission, or one task of it (code 0x0E03)."""

    mission_id: int
    """The mission."""
    task_id: int
    """The task to pause; 0 pauses the whole mission."""
    def __init__(self, *, mission_id: int = ..., task_id: int = ...) -> None: ...

class ResumeMission(Message):
    """Resumes a paused mission, or one task of it (code 0x0E04)."""

    mission_id: int
    """The mission."""
    task_id: int
    """The task to resume; 0 resumes the whole mission."""
    def __init__(self, *, mission_id: int = ..., task_id: int = ...) -> None: ...

class RemoveMessages(Message):
    """Removes messages from a task of a spooled mission (code 0x0E05)."""

    mission_id: int
    """The mission."""
    task_id: int
    """The task."""
    uids: List[int]
    """Unique IDs of the messages to remove."""
    def __init__(self, *, mission_id: int = ..., task_id: int = ..., uids: List[int] = ...) -> None: ...

class ReplaceMessages(Message):
    """Edits a task of a spooled mission: removes the messages with the given unique IDs and inserts new mission commands (code 0x0E06)."""

    mission_id: int
    """The mission."""
    task_id: int
    """The task."""
    uids: List[int]
    """Unique IDs of the messages to remove."""
    commands: List[Record]
    """The mission commands to insert."""
    def __init__(self, *, mission_id: int = ..., task_id: int = ..., uids: List[int] = ..., commands: List[_RecordIn] = ...) -> None: ...

class QuerySpoolingPreference(Message):
    """Asks a mission spooler how much of a mission it wants spooled at a time (Part 1 calls it "Spooling Preferences") (code 0x2E00)."""

    def __init__(self) -> None: ...

class QueryMissionStatus(Message):
    """Asks for the status of a mission, task or message. The presence vector is data here: OpenJAUS always sends and reads every field, whatever its bits say (code 0x2E01)."""

    presence_vector: int
    """Which IDs are meant: bit 0 mission ID, bit 1 task ID, bit 2 message uid."""
    status_type: Union[Literal["Mission", "Task", "Message"], Record]
    """Whether the mission, a task or a message is asked about."""
    mission_id: int
    """The mission."""
    task_id: int
    """The task."""
    task_msg_id: int
    """Unique ID of the message."""
    def __init__(self, *, presence_vector: int = ..., status_type: Union[Literal["Mission", "Task", "Message"], _RecordIn] = ..., mission_id: int = ..., task_id: int = ..., task_msg_id: int = ...) -> None: ...

class ReportSpoolingPreference(Message):
    """How much of a mission the spooler wants spooled at a time, answering Query Spooling Preference (code 0x4E00)."""

    spool_type: Union[Literal["MessageCount", "Distance", "Time"], Record]
    """What the limit counts."""
    data: int
    """The limit: messages, metres or seconds, as the limit type says."""
    def __init__(self, *, spool_type: Union[Literal["MessageCount", "Distance", "Time"], _RecordIn] = ..., data: int = ...) -> None: ...

class ReportMissionStatus(Message):
    """The status of a mission, task or message, answering Query Mission Status (code 0x4E01)."""

    status_type: Union[Literal["Mission", "Task", "Message"], Record]
    """Whether the status is of the mission, a task or a message."""
    status: Union[Literal["Spooling", "Pending", "Paused", "Aborted", "Finished"], Record]
    """The state."""
    secondary_status: Union[Literal["NoError", "LostComponentControl", "ToleranceNotMet"], Record]
    """Additional information, e.g. an error."""
    mission_id: int
    """The mission."""
    task_id: int
    """The task (0 when the status is of the mission)."""
    task_msg_id: int
    """Unique ID of the message."""
    def __init__(self, *, status_type: Union[Literal["Mission", "Task", "Message"], _RecordIn] = ..., status: Union[Literal["Spooling", "Pending", "Paused", "Aborted", "Finished"], _RecordIn] = ..., secondary_status: Union[Literal["NoError", "LostComponentControl", "ToleranceNotMet"], _RecordIn] = ..., mission_id: int = ..., task_id: int = ..., task_msg_id: int = ...) -> None: ...

class SpoolMission(Message):
    """Stores a mission (an N-ary tree of tasks holding JAUS messages) in the Mission Spooler, replacing or appending to the current one (code 0x0E00)."""

    mission_id: int
    """Mission identifier."""
    append_flag: int
    """0 replaces the current mission, 1 appends to it."""
    root: Record
    """The root task of the mission's task tree."""
    def __init__(self, *, mission_id: int = ..., append_flag: int = ..., root: _RecordIn = ...) -> None: ...

class SetVelocityState(Message):
    """Commands the platform's linear velocities and rotational rates (OpenJAUS experimental; not part of RA 3.3). Same layout as Report Velocity State (code 0x0404)."""

    velocity_x: Optional[float]
    """Unit: m/s. Optional: presence bit 0. Velocity along the X axis."""
    velocity_y: Optional[float]
    """Unit: m/s. Optional: presence bit 1. Velocity along the Y axis."""
    velocity_z: Optional[float]
    """Unit: m/s. Optional: presence bit 2. Velocity along the Z axis."""
    velocity_rms: Optional[float]
    """Unit: m/s. Optional: presence bit 3. RMS error of the velocity."""
    roll_rate: Optional[float]
    """Unit: rad/s. Optional: presence bit 4. Rate about the X axis."""
    pitch_rate: Optional[float]
    """Unit: rad/s. Optional: presence bit 5. Rate about the Y axis."""
    yaw_rate: Optional[float]
    """Unit: rad/s. Optional: presence bit 6. Rate about the Z axis."""
    rate_rms: Optional[float]
    """Unit: rad/s. Optional: presence bit 7. RMS error of the rotational rates."""
    time_stamp: Optional[Record]
    """Optional: presence bit 8. Time the state applies to."""
    def __init__(self, *, velocity_x: float = ..., velocity_y: float = ..., velocity_z: float = ..., velocity_rms: float = ..., roll_rate: float = ..., pitch_rate: float = ..., yaw_rate: float = ..., rate_rms: float = ..., time_stamp: _RecordIn = ...) -> None: ...

class SetWrenchEffort(Message):
    """Commands the primitive driver's propulsive and resistive efforts, in percent of the maximum (typical ground vehicle: bit 0 throttle, bit 5 steering, bit 6 brake) (code 0x0405)."""

    propulsive_linear_effort_x: Optional[float]
    """Unit: %. Optional: presence bit 0. Propulsive linear effort along X."""
    propulsive_linear_effort_y: Optional[float]
    """Unit: %. Optional: presence bit 1. Propulsive linear effort along Y."""
    propulsive_linear_effort_z: Optional[float]
    """Unit: %. Optional: presence bit 2. Propulsive linear effort along Z."""
    propulsive_rotational_effort_x: Optional[float]
    """Unit: %. Optional: presence bit 3. Propulsive rotational effort about X."""
    propulsive_rotational_effort_y: Optional[float]
    """Unit: %. Optional: presence bit 4. Propulsive rotational effort about Y."""
    propulsive_rotational_effort_z: Optional[float]
    """Unit: %. Optional: presence bit 5. Propulsive rotational effort about Z."""
    resistive_linear_effort_x: Optional[float]
    """Unit: %. Optional: presence bit 6. Resistive linear effort along X."""
    resistive_linear_effort_y: Optional[float]
    """Unit: %. Optional: presence bit 7. Resistive linear effort along Y."""
    resistive_linear_effort_z: Optional[float]
    """Unit: %. Optional: presence bit 8. Resistive linear effort along Z."""
    resistive_rotational_effort_x: Optional[float]
    """Unit: %. Optional: presence bit 9. Resistive rotational effort about X."""
    resistive_rotational_effort_y: Optional[float]
    """Unit: %. Optional: presence bit 10. Resistive rotational effort about Y."""
    resistive_rotational_effort_z: Optional[float]
    """Unit: %. Optional: presence bit 11. Resistive rotational effort about Z."""
    def __init__(self, *, propulsive_linear_effort_x: float = ..., propulsive_linear_effort_y: float = ..., propulsive_linear_effort_z: float = ..., propulsive_rotational_effort_x: float = ..., propulsive_rotational_effort_y: float = ..., propulsive_rotational_effort_z: float = ..., resistive_linear_effort_x: float = ..., resistive_linear_effort_y: float = ..., resistive_linear_effort_z: float = ..., resistive_rotational_effort_x: float = ..., resistive_rotational_effort_y: float = ..., resistive_rotational_effort_z: float = ...) -> None: ...

class SetDiscreteDevices(Message):
    """Commands the platform's discrete devices (propulsion, parking brake, horn, gear, transfer case) (code 0x0406)."""

    propulsion: Optional[Record]
    """Optional: presence bit 0. Main propulsion, fuel, auxiliary power and starting bits."""
    parking_brake_and_horn: Optional[Record]
    """Optional: presence bit 1. Parking brake and horn bits."""
    gear: Optional[int]
    """Optional: presence bit 2. Selected gear (raw value)."""
    transfer_case: Optional[int]
    """Optional: presence bit 3. Transfer-case setting (raw value)."""
    def __init__(self, *, propulsion: _RecordIn = ..., parking_brake_and_horn: _RecordIn = ..., gear: int = ..., transfer_case: int = ...) -> None: ...

class SetGlobalVector(Message):
    """Commands the global vector driver's desired speed, altitude and attitude (heading 0 = North) (code 0x0407)."""

    speed: Optional[float]
    """Unit: m/s. Optional: presence bit 0. Desired speed."""
    altitude: Optional[float]
    """Unit: m. Optional: presence bit 1. Desired altitude above sea level (WGS84)."""
    heading: Optional[float]
    """Unit: rad. Optional: presence bit 2. Desired heading; 0 is North."""
    roll: Optional[float]
    """Unit: rad. Optional: presence bit 3. Desired roll."""
    pitch: Optional[float]
    """Unit: rad. Optional: presence bit 4. Desired pitch."""
    def __init__(self, *, speed: float = ..., altitude: float = ..., heading: float = ..., roll: float = ..., pitch: float = ...) -> None: ...

class SetLocalVector(Message):
    """Commands the local vector driver's desired speed and heading (heading 0 = local +X). OpenJAUS carries only these two fields, the speed as a signed integer (code 0x0408)."""

    speed: float
    """Unit: m/s. Desired speed (signed type, so the bias is 5000)."""
    heading: float
    """Unit: rad. Desired heading; 0 is the local +X axis."""
    def __init__(self, *, speed: float = ..., heading: float = ...) -> None: ...

class SetTravelSpeed(Message):
    """Sets the travel speed the waypoint and path-segment drivers use (code 0x040A)."""

    speed: float
    """Unit: m/s. Travel speed."""
    def __init__(self, *, speed: float = ...) -> None: ...

class SetGlobalWaypoint(Message):
    """Adds a waypoint, in global (WGS84) coordinates, to the global waypoint driver's list (code 0x040C)."""

    waypoint_number: int
    """Number of the waypoint in the list."""
    latitude: float
    """Unit: deg. Latitude (WGS84)."""
    longitude: float
    """Unit: deg. Longitude (WGS84)."""
    elevation: Optional[float]
    """Unit: m. Optional: presence bit 0. Elevation above sea level."""
    roll: Optional[float]
    """Unit: rad. Optional: presence bit 1. Roll at the waypoint."""
    pitch: Optional[float]
    """Unit: rad. Optional: presence bit 2. Pitch at the waypoint."""
    yaw: Optional[float]
    """Unit: rad. Optional: presence bit 3. Yaw (heading) at the waypoint; 0 is North."""
    def __init__(self, *, waypoint_number: int = ..., latitude: float = ..., longitude: float = ..., elevation: float = ..., roll: float = ..., pitch: float = ..., yaw: float = ...) -> None: ...

class SetLocalWaypoint(Message):
    """Adds a waypoint, in local coordinates, to the local waypoint driver's list (code 0x040D)."""

    waypoint_number: int
    """Number of the waypoint in the list."""
    x: float
    """Unit: m. X coordinate."""
    y: float
    """Unit: m. Y coordinate."""
    z: Optional[float]
    """Unit: m. Optional: presence bit 0. Z coordinate."""
    roll: Optional[float]
    """Unit: rad. Optional: presence bit 1. Roll at the waypoint."""
    pitch: Optional[float]
    """Unit: rad. Optional: presence bit 2. Pitch at the waypoint."""
    yaw: Optional[float]
    """Unit: rad. Optional: presence bit 3. Yaw at the waypoint; 0 is the local +X axis."""
    def __init__(self, *, waypoint_number: int = ..., x: float = ..., y: float = ..., z: float = ..., roll: float = ..., pitch: float = ..., yaw: float = ...) -> None: ...

class SetGlobalPathSegment(Message):
    """Adds a path segment (a curve from P0 through control point P1 to P2 with weighting w1), in global coordinates, to the global path-segment driver. P0 is not sent: it is the current position for segment 0, otherwise the previous segment's P2 (code 0x040F)."""

    path_segment_number: int
    """Number of the segment; starts at 0."""
    p1_latitude: float
    """Unit: deg. Latitude of P1."""
    p1_longitude: float
    """Unit: deg. Longitude of P1."""
    p1_altitude: Optional[float]
    """Unit: m. Optional: presence bit 0. Altitude of P1."""
    p2_latitude: float
    """Unit: deg. Latitude of P2."""
    p2_longitude: float
    """Unit: deg. Longitude of P2."""
    p2_altitude: Optional[float]
    """Unit: m. Optional: presence bit 1. Altitude of P2."""
    weighting_factor: float
    """Weighting factor w1 of the curve."""
    def __init__(self, *, path_segment_number: int = ..., p1_latitude: float = ..., p1_longitude: float = ..., p1_altitude: float = ..., p2_latitude: float = ..., p2_longitude: float = ..., p2_altitude: float = ..., weighting_factor: float = ...) -> None: ...

class SetLocalPathSegment(Message):
    """Adds a path segment (P0, P1, P2, weighting w1), in local coordinates, to the local path-segment driver. P0 is not sent (see Set Global Path Segment) (code 0x0410)."""

    path_segment_number: int
    """Number of the segment; starts at 0."""
    p1_x: float
    """Unit: m. X coordinate of P1."""
    p1_y: float
    """Unit: m. Y coordinate of P1."""
    p1_z: Optional[float]
    """Unit: m. Optional: presence bit 0. Z coordinate of P1."""
    p2_x: float
    """Unit: m. X coordinate of P2."""
    p2_y: float
    """Unit: m. Y coordinate of P2."""
    p2_z: Optional[float]
    """Unit: m. Optional: presence bit 1. Z coordinate of P2."""
    weighting_factor: float
    """Weighting factor w1 of the curve."""
    def __init__(self, *, path_segment_number: int = ..., p1_x: float = ..., p1_y: float = ..., p1_z: float = ..., p2_x: float = ..., p2_y: float = ..., p2_z: float = ..., weighting_factor: float = ...) -> None: ...

class QueryPlatformSpecifications(Message):
    """Asks for the platform's specifications (code 0x2400)."""

    presence_vector: int
    """Fields wanted in Report Platform Specifications."""
    def __init__(self, *, presence_vector: int = ...) -> None: ...

class QueryPlatformOperationalData(Message):
    """Asks for the platform's operational data (code 0x2401)."""

    presence_vector: int
    """Fields wanted in Report Platform Operational Data."""
    def __init__(self, *, presence_vector: int = ...) -> None: ...

class QueryGlobalPose(Message):
    """Asks for the platform's global pose (code 0x2402)."""

    presence_vector: int
    """Fields wanted in Report Global Pose."""
    def __init__(self, *, presence_vector: int = ...) -> None: ...

class QueryLocalPose(Message):
    """Asks for the platform's local pose (code 0x2403)."""

    presence_vector: int
    """Fields wanted in Report Local Pose."""
    def __init__(self, *, presence_vector: int = ...) -> None: ...

class QueryVelocityState(Message):
    """Asks for the platform's velocity state (code 0x2404)."""

    presence_vector: int
    """Fields wanted in Report Velocity State."""
    def __init__(self, *, presence_vector: int = ...) -> None: ...

class QueryWrenchEffort(Message):
    """Asks for the primitive driver's current wrench effort (code 0x2405)."""

    presence_vector: int
    """Fields wanted in Report Wrench Effort."""
    def __init__(self, *, presence_vector: int = ...) -> None: ...

class QueryDiscreteDevices(Message):
    """Asks for the state of the platform's discrete devices (code 0x2406)."""

    presence_vector: int
    """Fields wanted in Report Discrete Devices."""
    def __init__(self, *, presence_vector: int = ...) -> None: ...

class QueryGlobalVector(Message):
    """Asks for the global vector driver's current desired vector (code 0x2407)."""

    presence_vector: int
    """Fields wanted in Report Global Vector."""
    def __init__(self, *, presence_vector: int = ...) -> None: ...

class QueryLocalVector(Message):
    """Asks for the local vector driver's current desired vector (code 0x2408)."""

    def __init__(self) -> None: ...

class QueryTravelSpeed(Message):
    """Asks for the current travel speed (code 0x240A)."""

    def __init__(self) -> None: ...

class QueryWaypointCount(Message):
    """Asks how many waypoints the (global or local) waypoint driver holds (code 0x240B)."""

    def __init__(self) -> None: ...

class QueryGlobalWaypoint(Message):
    """Asks for one waypoint of the global waypoint driver (code 0x240C)."""

    waypoint_number: int
    """Number of the waypoint wanted."""
    def __init__(self, *, waypoint_number: int = ...) -> None: ...

class QueryLocalWaypoint(Message):
    """Asks for one waypoint of the local waypoint driver (code 0x240D)."""

    waypoint_number: int
    """Number of the waypoint wanted."""
    def __init__(self, *, waypoint_number: int = ...) -> None: ...

class QueryPathSegmentCount(Message):
    """Asks how many path segments the (global or local) path-segment driver holds (code 0x240E)."""

    def __init__(self) -> None: ...

class QueryGlobalPathSegment(Message):
    """Asks for one path segment of the global path-segment driver. OpenJAUS sends the segment number before the presence vector (code 0x240F)."""

    path_segment_number: int
    """Number of the segment wanted."""
    presence_vector: int
    """Fields wanted in Report Global Path Segment."""
    def __init__(self, *, path_segment_number: int = ..., presence_vector: int = ...) -> None: ...

class QueryLocalPathSegment(Message):
    """Asks for one path segment of the local path-segment driver. OpenJAUS sends the segment number before the presence vector (code 0x2410)."""

    path_segment_number: int
    """Number of the segment wanted."""
    presence_vector: int
    """Fields wanted in Report Local Path Segment."""
    def __init__(self, *, path_segment_number: int = ..., presence_vector: int = ...) -> None: ...

class ReportPlatformSpecifications(Message):
    """The platform's name, dimensions, centre of gravity, stability limits and maximum rates (code 0x4400)."""

    platform_name: Optional[str]
    """Optional: presence bit 0. Platform name, NUL-padded to 15 bytes."""
    front: Optional[float]
    """Unit: m. Optional: presence bit 1. Distance from the vehicle origin to the front."""
    back: Optional[float]
    """Unit: m. Optional: presence bit 2. Distance from the vehicle origin to the back."""
    right: Optional[float]
    """Unit: m. Optional: presence bit 3. Distance from the vehicle origin to the right side."""
    left: Optional[float]
    """Unit: m. Optional: presence bit 4. Distance from the vehicle origin to the left side."""
    bottom: Optional[float]
    """Unit: m. Optional: presence bit 5. Distance from the vehicle origin to the bottom."""
    top: Optional[float]
    """Unit: m. Optional: presence bit 6. Distance from the vehicle origin to the top."""
    x_cg: Optional[float]
    """Unit: m. Optional: presence bit 7. X coordinate of the centre of gravity."""
    y_cg: Optional[float]
    """Unit: m. Optional: presence bit 8. Y coordinate of the centre of gravity."""
    z_cg: Optional[float]
    """Unit: m. Optional: presence bit 9. Z coordinate of the centre of gravity."""
    turning_radius: Optional[float]
    """Unit: m. Optional: presence bit 10. Minimum turning radius."""
    wheel_base: Optional[float]
    """Unit: m. Optional: presence bit 11. Wheel base."""
    track_width: Optional[float]
    """Unit: m. Optional: presence bit 12. Track width."""
    pitch_over: Optional[float]
    """Unit: rad. Optional: presence bit 13. Pitch angle at which the platform tips over."""
    roll_over: Optional[float]
    """Unit: rad. Optional: presence bit 14. Roll angle at which the platform rolls over."""
    maximum_velocity_x: Optional[float]
    """Unit: m/s. Optional: presence bit 15. Maximum velocity along X."""
    maximum_velocity_y: Optional[float]
    """Unit: m/s. Optional: presence bit 16. Maximum velocity along Y."""
    maximum_velocity_z: Optional[float]
    """Unit: m/s. Optional: presence bit 17. Maximum velocity along Z."""
    maximum_roll_rate: Optional[float]
    """Unit: rad/s. Optional: presence bit 18. Maximum roll rate."""
    maximum_pitch_rate: Optional[float]
    """Unit: rad/s. Optional: presence bit 19. Maximum pitch rate."""
    maximum_yaw_rate: Optional[float]
    """Unit: rad/s. Optional: presence bit 20. Maximum yaw rate."""
    def __init__(self, *, platform_name: str = ..., front: float = ..., back: float = ..., right: float = ..., left: float = ..., bottom: float = ..., top: float = ..., x_cg: float = ..., y_cg: float = ..., z_cg: float = ..., turning_radius: float = ..., wheel_base: float = ..., track_width: float = ..., pitch_over: float = ..., roll_over: float = ..., maximum_velocity_x: float = ..., maximum_velocity_y: float = ..., maximum_velocity_z: float = ..., maximum_roll_rate: float = ..., maximum_pitch_rate: float = ..., maximum_yaw_rate: float = ...) -> None: ...

class ReportPlatformOperationalData(Message):
    """The platform's engine temperature, odometer, battery voltage, fuel level and oil pressure (code 0x4401)."""

    engine_temperature: Optional[float]
    """Unit: °C. Optional: presence bit 0. Engine temperature."""
    odometer: Optional[int]
    """Unit: m. Optional: presence bit 1. Distance travelled (raw, not scaled)."""
    battery_voltage: Optional[float]
    """Unit: %. Optional: presence bit 2. Battery voltage, in percent of nominal."""
    fuel_level: Optional[float]
    """Unit: %. Optional: presence bit 3. Fuel level."""
    oil_pressure: Optional[float]
    """Unit: %. Optional: presence bit 4. Oil pressure, in percent of nominal."""
    def __init__(self, *, engine_temperature: float = ..., odometer: int = ..., battery_voltage: float = ..., fuel_level: float = ..., oil_pressure: float = ...) -> None: ...

class ReportGlobalPose(Message):
    """The platform's position (WGS84) and attitude, with their RMS errors and time (code 0x4402)."""

    latitude: Optional[float]
    """Unit: deg. Optional: presence bit 0. Latitude (WGS84)."""
    longitude: Optional[float]
    """Unit: deg. Optional: presence bit 1. Longitude (WGS84)."""
    elevation: Optional[float]
    """Unit: m. Optional: presence bit 2. Elevation above sea level."""
    position_rms: Optional[float]
    """Unit: m. Optional: presence bit 3. RMS error of the position."""
    roll: Optional[float]
    """Unit: rad. Optional: presence bit 4. Roll."""
    pitch: Optional[float]
    """Unit: rad. Optional: presence bit 5. Pitch."""
    yaw: Optional[float]
    """Unit: rad. Optional: presence bit 6. Yaw (heading); 0 is North."""
    attitude_rms: Optional[float]
    """Unit: rad. Optional: presence bit 7. RMS error of the attitude."""
    time_stamp: Optional[Record]
    """Optional: presence bit 8. Time of the measurement."""
    def __init__(self, *, latitude: float = ..., longitude: float = ..., elevation: float = ..., position_rms: float = ..., roll: float = ..., pitch: float = ..., yaw: float = ..., attitude_rms: float = ..., time_stamp: _RecordIn = ...) -> None: ...

class ReportLocalPose(Message):
    """The platform's position and attitude in local coordinates, with their RMS errors and time (code 0x4403)."""

    x: Optional[float]
    """Unit: m. Optional: presence bit 0. X coordinate."""
    y: Optional[float]
    """Unit: m. Optional: presence bit 1. Y coordinate."""
    z: Optional[float]
    """Unit: m. Optional: presence bit 2. Z coordinate."""
    position_rms: Optional[float]
    """Unit: m. Optional: presence bit 3. RMS error of the position."""
    roll: Optional[float]
    """Unit: rad. Optional: presence bit 4. Roll."""
    pitch: Optional[float]
    """Unit: rad. Optional: presence bit 5. Pitch."""
    yaw: Optional[float]
    """Unit: rad. Optional: presence bit 6. Yaw; 0 is the local +X axis."""
    attitude_rms: Optional[float]
    """Unit: rad. Optional: presence bit 7. RMS error of the attitude."""
    time_stamp: Optional[Record]
    """Optional: presence bit 8. Time of the measurement."""
    def __init__(self, *, x: float = ..., y: float = ..., z: float = ..., position_rms: float = ..., roll: float = ..., pitch: float = ..., yaw: float = ..., attitude_rms: float = ..., time_stamp: _RecordIn = ...) -> None: ...

class ReportVelocityState(Message):
    """The platform's linear velocities and rotational rates, with their RMS errors and time (code 0x4404)."""

    velocity_x: Optional[float]
    """Unit: m/s. Optional: presence bit 0. Velocity along the X axis."""
    velocity_y: Optional[float]
    """Unit: m/s. Optional: presence bit 1. Velocity along the Y axis."""
    velocity_z: Optional[float]
    """Unit: m/s. Optional: presence bit 2. Velocity along the Z axis."""
    velocity_rms: Optional[float]
    """Unit: m/s. Optional: presence bit 3. RMS error of the velocity."""
    roll_rate: Optional[float]
    """Unit: rad/s. Optional: presence bit 4. Rate about the X axis."""
    pitch_rate: Optional[float]
    """Unit: rad/s. Optional: presence bit 5. Rate about the Y axis."""
    yaw_rate: Optional[float]
    """Unit: rad/s. Optional: presence bit 6. Rate about the Z axis."""
    rate_rms: Optional[float]
    """Unit: rad/s. Optional: presence bit 7. RMS error of the rotational rates."""
    time_stamp: Optional[Record]
    """Optional: presence bit 8. Time of the measurement."""
    def __init__(self, *, velocity_x: float = ..., velocity_y: float = ..., velocity_z: float = ..., velocity_rms: float = ..., roll_rate: float = ..., pitch_rate: float = ..., yaw_rate: float = ..., rate_rms: float = ..., time_stamp: _RecordIn = ...) -> None: ...

class ReportWrenchEffort(Message):
    """The primitive driver's current propulsive and resistive efforts, in percent of the maximum (code 0x4405)."""

    propulsive_linear_effort_x: Optional[float]
    """Unit: %. Optional: presence bit 0. Propulsive linear effort along X."""
    propulsive_linear_effort_y: Optional[float]
    """Unit: %. Optional: presence bit 1. Propulsive linear effort along Y."""
    propulsive_linear_effort_z: Optional[float]
    """Unit: %. Optional: presence bit 2. Propulsive linear effort along Z."""
    propulsive_rotational_effort_x: Optional[float]
    """Unit: %. Optional: presence bit 3. Propulsive rotational effort about X."""
    propulsive_rotational_effort_y: Optional[float]
    """Unit: %. Optional: presence bit 4. Propulsive rotational effort about Y."""
    propulsive_rotational_effort_z: Optional[float]
    """Unit: %. Optional: presence bit 5. Propulsive rotational effort about Z."""
    resistive_linear_effort_x: Optional[float]
    """Unit: %. Optional: presence bit 6. Resistive linear effort along X."""
    resistive_linear_effort_y: Optional[float]
    """Unit: %. Optional: presence bit 7. Resistive linear effort along Y."""
    resistive_linear_effort_z: Optional[float]
    """Unit: %. Optional: presence bit 8. Resistive linear effort along Z."""
    resistive_rotational_effort_x: Optional[float]
    """Unit: %. Optional: presence bit 9. Resistive rotational effort about X."""
    resistive_rotational_effort_y: Optional[float]
    """Unit: %. Optional: presence bit 10. Resistive rotational effort about Y."""
    resistive_rotational_effort_z: Optional[float]
    """Unit: %. Optional: presence bit 11. Resistive rotational effort about Z."""
    def __init__(self, *, propulsive_linear_effort_x: float = ..., propulsive_linear_effort_y: float = ..., propulsive_linear_effort_z: float = ..., propulsive_rotational_effort_x: float = ..., propulsive_rotational_effort_y: float = ..., propulsive_rotational_effort_z: float = ..., resistive_linear_effort_x: float = ..., resistive_linear_effort_y: float = ..., resistive_linear_effort_z: float = ..., resistive_rotational_effort_x: float = ..., resistive_rotational_effort_y: float = ..., resistive_rotational_effort_z: float = ...) -> None: ...

class ReportDiscreteDevices(Message):
    """The state of the platform's discrete devices (propulsion, parking brake, horn, gear, transfer case) (code 0x4406)."""

    propulsion: Optional[Record]
    """Optional: presence bit 0. Main propulsion, fuel, auxiliary power and starting bits."""
    parking_brake_and_horn: Optional[Record]
    """Optional: presence bit 1. Parking brake and horn bits."""
    gear: Optional[int]
    """Optional: presence bit 2. Selected gear (raw value)."""
    transfer_case: Optional[int]
    """Optional: presence bit 3. Transfer-case setting (raw value)."""
    def __init__(self, *, propulsion: _RecordIn = ..., parking_brake_and_horn: _RecordIn = ..., gear: int = ..., transfer_case: int = ...) -> None: ...

class ReportGlobalVector(Message):
    """The global vector driver's current desired speed, altitude and attitude (code 0x4407)."""

    speed: Optional[float]
    """Unit: m/s. Optional: presence bit 0. Desired speed."""
    altitude: Optional[float]
    """Unit: m. Optional: presence bit 1. Desired altitude above sea level (WGS84)."""
    heading: Optional[float]
    """Unit: rad. Optional: presence bit 2. Desired heading; 0 is North."""
    roll: Optional[float]
    """Unit: rad. Optional: presence bit 3. Desired roll."""
    pitch: Optional[float]
    """Unit: rad. Optional: presence bit 4. Desired pitch."""
    def __init__(self, *, speed: float = ..., altitude: float = ..., heading: float = ..., roll: float = ..., pitch: float = ...) -> None: ...

class ReportLocalVector(Message):
    """The local vector driver's current desired speed and heading (code 0x4408)."""

    speed: float
    """Unit: m/s. Desired speed (signed type, so the bias is 5000)."""
    heading: float
    """Unit: rad. Desired heading; 0 is the local +X axis."""
    def __init__(self, *, speed: float = ..., heading: float = ...) -> None: ...

class ReportTravelSpeed(Message):
    """The current travel speed of the waypoint and path-segment drivers (code 0x440A)."""

    speed: float
    """Unit: m/s. Travel speed."""
    def __init__(self, *, speed: float = ...) -> None: ...

class ReportWaypointCount(Message):
    """How many waypoints the (global or local) waypoint driver holds (code 0x440B)."""

    waypoint_count: int
    """Number of waypoints."""
    def __init__(self, *, waypoint_count: int = ...) -> None: ...

class ReportGlobalWaypoint(Message):
    """One waypoint of the global waypoint driver (code 0x440C)."""

    waypoint_number: int
    """Number of the waypoint in the list."""
    latitude: float
    """Unit: deg. Latitude (WGS84)."""
    longitude: float
    """Unit: deg. Longitude (WGS84)."""
    elevation: Optional[float]
    """Unit: m. Optional: presence bit 0. Elevation above sea level."""
    roll: Optional[float]
    """Unit: rad. Optional: presence bit 1. Roll at the waypoint."""
    pitch: Optional[float]
    """Unit: rad. Optional: presence bit 2. Pitch at the waypoint."""
    yaw: Optional[float]
    """Unit: rad. Optional: presence bit 3. Yaw (heading) at the waypoint; 0 is North."""
    def __init__(self, *, waypoint_number: int = ..., latitude: float = ..., longitude: float = ..., elevation: float = ..., roll: float = ..., pitch: float = ..., yaw: float = ...) -> None: ...

class ReportLocalWaypoint(Message):
    """One waypoint of the local waypoint driver (code 0x440D)."""

    waypoint_number: int
    """Number of the waypoint in the list."""
    x: float
    """Unit: m. X coordinate."""
    y: float
    """Unit: m. Y coordinate."""
    z: Optional[float]
    """Unit: m. Optional: presence bit 0. Z coordinate."""
    roll: Optional[float]
    """Unit: rad. Optional: presence bit 1. Roll at the waypoint."""
    pitch: Optional[float]
    """Unit: rad. Optional: presence bit 2. Pitch at the waypoint."""
    yaw: Optional[float]
    """Unit: rad. Optional: presence bit 3. Yaw at the waypoint; 0 is the local +X axis."""
    def __init__(self, *, waypoint_number: int = ..., x: float = ..., y: float = ..., z: float = ..., roll: float = ..., pitch: float = ..., yaw: float = ...) -> None: ...

class ReportPathSegmentCount(Message):
    """How many path segments the (global or local) path-segment driver holds (code 0x440E)."""

    path_segment_count: int
    """Number of path segments."""
    def __init__(self, *, path_segment_count: int = ...) -> None: ...

class ReportGlobalPathSegment(Message):
    """One path segment (P1, P2, weighting w1) of the global path-segment driver (code 0x440F)."""

    path_segment_number: int
    """Number of the segment; starts at 0."""
    p1_latitude: float
    """Unit: deg. Latitude of P1."""
    p1_longitude: float
    """Unit: deg. Longitude of P1."""
    p1_altitude: Optional[float]
    """Unit: m. Optional: presence bit 0. Altitude of P1."""
    p2_latitude: float
    """Unit: deg. Latitude of P2."""
    p2_longitude: float
    """Unit: deg. Longitude of P2."""
    p2_altitude: Optional[float]
    """Unit: m. Optional: presence bit 1. Altitude of P2."""
    weighting_factor: float
    """Weighting factor w1 of the curve."""
    def __init__(self, *, path_segment_number: int = ..., p1_latitude: float = ..., p1_longitude: float = ..., p1_altitude: float = ..., p2_latitude: float = ..., p2_longitude: float = ..., p2_altitude: float = ..., weighting_factor: float = ...) -> None: ...

class ReportLocalPathSegment(Message):
    """One path segment (P1, P2, weighting w1) of the local path-segment driver (code 0x4410)."""

    path_segment_number: int
    """Number of the segment; starts at 0."""
    p1_x: float
    """Unit: m. X coordinate of P1."""
    p1_y: float
    """Unit: m. Y coordinate of P1."""
    p1_z: Optional[float]
    """Unit: m. Optional: presence bit 0. Z coordinate of P1."""
    p2_x: float
    """Unit: m. X coordinate of P2."""
    p2_y: float
    """Unit: m. Y coordinate of P2."""
    p2_z: Optional[float]
    """Unit: m. Optional: presence bit 1. Z coordinate of P2."""
    weighting_factor: float
    """Weighting factor w1 of the curve."""
    def __init__(self, *, path_segment_number: int = ..., p1_x: float = ..., p1_y: float = ..., p1_z: float = ..., p2_x: float = ..., p2_y: float = ..., p2_z: float = ..., weighting_factor: float = ...) -> None: ...

class SetVksFeatureClassMetadata(Message):
    """Changes the metadata text of a feature class (code 0x0A21)."""

    metadata_option: Union[Literal["Append", "Prepend", "Overwrite", "Erase"], Record]
    """Append, prepend, overwrite or erase."""
    feature_class_id: int
    """The feature class."""
    metadata: str
    """Metadata text, with a u16 length prefix."""
    def __init__(self, *, metadata_option: Union[Literal["Append", "Prepend", "Overwrite", "Erase"], _RecordIn] = ..., feature_class_id: int = ..., metadata: str = ...) -> None: ...

class TerminateVksDataTransfer(Message):
    """Stops a data transfer in progress (e.g. the objects of Report VKS Objects) (code 0x0A24)."""

    def __init__(self) -> None: ...

class QueryVksFeatureClassMetadata(Message):
    """Asks for the metadata text of a feature class (code 0x2A21)."""

    feature_class_id: int
    """The feature class."""
    def __init__(self, *, feature_class_id: int = ...) -> None: ...

class QueryVksBounds(Message):
    """Asks for the bounding box of the objects of a feature class (code 0x2A22)."""

    request_id: int
    """Chosen by the requester; echoed in the report."""
    feature_class_id: int
    """The feature class."""
    def __init__(self, *, request_id: int = ..., feature_class_id: int = ...) -> None: ...

class ReportVksObjectsCreation(Message):
    """The IDs of the objects created by Create VKS Objects, when the requester asked for them (code 0x4A20)."""

    request_id: int
    """Request ID of the Create VKS Objects message."""
    object_ids: List[int]
    """IDs of the created objects, in request order; 0 marks an object that could not be created."""
    def __init__(self, *, request_id: int = ..., object_ids: List[int] = ...) -> None: ...

class ReportVksFeatureClassMetadata(Message):
    """The metadata text of a feature class, answering Query VKS Feature Class Metadata (code 0x4A21)."""

    feature_class_id: int
    """The feature class."""
    metadata: str
    """Metadata text, with a u16 length prefix."""
    def __init__(self, *, feature_class_id: int = ..., metadata: str = ...) -> None: ...

class ReportVksBounds(Message):
    """The bounding box of the objects of a feature class, answering Query VKS Bounds (code 0x4A22)."""

    request_id: int
    """Request ID of the query."""
    feature_class: int
    """Feature-class ID."""
    south_west_latitude: float
    """Unit: deg. Latitude of the south-west corner (WGS 84)."""
    south_west_longitude: float
    """Unit: deg. Longitude of the south-west corner (WGS 84)."""
    north_east_latitude: float
    """Unit: deg. Latitude of the north-east corner (WGS 84)."""
    north_east_longitude: float
    """Unit: deg. Longitude of the north-east corner (WGS 84)."""
    def __init__(self, *, request_id: int = ..., feature_class: int = ..., south_west_latitude: float = ..., south_west_longitude: float = ..., north_east_latitude: float = ..., north_east_longitude: float = ...) -> None: ...

class ReportVksDataTransferTermination(Message):
    """Confirms that a data transfer was stopped by Terminate VKS Data Transfer (code 0x4A24)."""

    def __init__(self) -> None: ...

class CreateVksObjects(Message):
    """Stores vector objects in the World Model Vector Knowledge Store (code 0x0A20)."""

    buffered: Optional[bool]
    """Optional: presence bit 0. Every object carries a region buffer."""
    message_properties: int
    """Bit 0: the requester wants Report VKS Objects Creation."""
    request_id: int
    """Echoed in Report VKS Objects Creation."""
    objects: List[Record]
    """Objects to create."""
    def __init__(self, *, buffered: bool = ..., message_properties: int = ..., request_id: int = ..., objects: List[_RecordIn] = ...) -> None: ...

class DeleteVksObjects(Message):
    """Deletes the objects selected by a filter: identifiers, a region (type, buffer and points), and feature-class identifiers and/or attributes (code 0x0A25)."""

    filter_by_class_ids: Optional[bool]
    """Optional: presence bit 4. Feature-class criteria carry class identifiers."""
    filter_by_attributes: Optional[bool]
    """Optional: presence bit 5. Feature-class criteria carry attribute values."""
    request_id: int
    """Request identifier."""
    object_ids: Optional[List[int]]
    """Optional: presence bit 0. Objects to delete by identifier."""
    region_type: Optional[Union[Literal["Point", "Line", "Polygon"], Record]]
    """Optional: presence bit 1. Type of the deletion region."""
    region_buffer: Optional[float]
    """Unit: m. Optional: presence bit 2. Buffer around the deletion region."""
    feature_classes: Optional[List[Record]]
    """Optional: presence bit 3. Feature-class criteria."""
    region_points: Optional[List[Record]]
    """Optional: presence bit 6. Vertices of the deletion region."""
    def __init__(self, *, filter_by_class_ids: bool = ..., filter_by_attributes: bool = ..., request_id: int = ..., object_ids: List[int] = ..., region_type: Union[Literal["Point", "Line", "Polygon"], _RecordIn] = ..., region_buffer: float = ..., feature_classes: List[_RecordIn] = ..., region_points: List[_RecordIn] = ...) -> None: ...

class QueryVksObjects(Message):
    """Asks for the objects selected by a filter (as in Delete VKS Objects); the response presence vector says what Report VKS Objects includes (code 0x2A23)."""

    filter_by_class_ids: Optional[bool]
    """Optional: presence bit 4. Feature-class criteria carry class identifiers."""
    filter_by_attributes: Optional[bool]
    """Optional: presence bit 5. Feature-class criteria carry attribute values."""
    response_presence_vector: int
    """Presence vector wanted in Report VKS Objects (bit 0: object data)."""
    request_id: int
    """Echoed in Report VKS Objects."""
    object_ids: Optional[List[int]]
    """Optional: presence bit 0. Objects to return by identifier."""
    region_type: Optional[Union[Literal["Point", "Line", "Polygon"], Record]]
    """Optional: presence bit 1. Type of the query region."""
    region_buffer: Optional[float]
    """Unit: m. Optional: presence bit 2. Buffer around the query region."""
    feature_classes: Optional[List[Record]]
    """Optional: presence bit 3. Feature-class criteria."""
    region_points: Optional[List[Record]]
    """Optional: presence bit 6. Vertices of the query region."""
    def __init__(self, *, filter_by_class_ids: bool = ..., filter_by_attributes: bool = ..., response_presence_vector: int = ..., request_id: int = ..., object_ids: List[int] = ..., region_type: Union[Literal["Point", "Line", "Polygon"], _RecordIn] = ..., region_buffer: float = ..., feature_classes: List[_RecordIn] = ..., region_points: List[_RecordIn] = ...) -> None: ...

class ReportVksObjects(Message):
    """The objects matching a Query VKS Objects: their number, and the objects themselves when the query asked for object data (code 0x4A23)."""

    request_id: int
    """From the query."""
    object_count: int
    """Number of matching objects (computed from `objects` when they are included)."""
    objects: Optional[List[Record]]
    """Optional: presence bit 0. The matching objects."""
    def __init__(self, *, request_id: int = ..., object_count: int = ..., objects: List[_RecordIn] = ...) -> None: ...

@overload
def message(name: Literal["SetDataLinkStatus"], /, **fields: Any) -> SetDataLinkStatus: ...
@overload
def message(name: Literal["SetDataLinkSelect"], /, **fields: Any) -> SetDataLinkSelect: ...
@overload
def message(name: Literal["SetSelectedDataLinkState"], /, **fields: Any) -> SetSelectedDataLinkState: ...
@overload
def message(name: Literal["QueryDataLinkStatus"], /, **fields: Any) -> QueryDataLinkStatus: ...
@overload
def message(name: Literal["QuerySelectedDataLinkStatus"], /, **fields: Any) -> QuerySelectedDataLinkStatus: ...
@overload
def message(name: Literal["QueryHeartbeatPulse"], /, **fields: Any) -> QueryHeartbeatPulse: ...
@overload
def message(name: Literal["ReportDataLinkStatus"], /, **fields: Any) -> ReportDataLinkStatus: ...
@overload
def message(name: Literal["ReportSelectedDataLinkStatus"], /, **fields: Any) -> ReportSelectedDataLinkStatus: ...
@overload
def message(name: Literal["ReportHeartbeatPulse"], /, **fields: Any) -> ReportHeartbeatPulse: ...
@overload
def message(name: Literal["SetComponentAuthority"], /, **fields: Any) -> SetComponentAuthority: ...
@overload
def message(name: Literal["Shutdown"], /, **fields: Any) -> Shutdown: ...
@overload
def message(name: Literal["Standby"], /, **fields: Any) -> Standby: ...
@overload
def message(name: Literal["Resume"], /, **fields: Any) -> Resume: ...
@overload
def message(name: Literal["Reset"], /, **fields: Any) -> Reset: ...
@overload
def message(name: Literal["SetEmergency"], /, **fields: Any) -> SetEmergency: ...
@overload
def message(name: Literal["ClearEmergency"], /, **fields: Any) -> ClearEmergency: ...
@overload
def message(name: Literal["CreateServiceConnection"], /, **fields: Any) -> CreateServiceConnection: ...
@overload
def message(name: Literal["ConfirmServiceConnection"], /, **fields: Any) -> ConfirmServiceConnection: ...
@overload
def message(name: Literal["ActivateServiceConnection"], /, **fields: Any) -> ActivateServiceConnection: ...
@overload
def message(name: Literal["SuspendServiceConnection"], /, **fields: Any) -> SuspendServiceConnection: ...
@overload
def message(name: Literal["TerminateServiceConnection"], /, **fields: Any) -> TerminateServiceConnection: ...
@overload
def message(name: Literal["RequestComponentControl"], /, **fields: Any) -> RequestComponentControl: ...
@overload
def message(name: Literal["ReleaseComponentControl"], /, **fields: Any) -> ReleaseComponentControl: ...
@overload
def message(name: Literal["ConfirmComponentControl"], /, **fields: Any) -> ConfirmComponentControl: ...
@overload
def message(name: Literal["RejectComponentControl"], /, **fields: Any) -> RejectComponentControl: ...
@overload
def message(name: Literal["SetTime"], /, **fields: Any) -> SetTime: ...
@overload
def message(name: Literal["QueryComponentAuthority"], /, **fields: Any) -> QueryComponentAuthority: ...
@overload
def message(name: Literal["QueryComponentStatus"], /, **fields: Any) -> QueryComponentStatus: ...
@overload
def message(name: Literal["QueryComponentControl"], /, **fields: Any) -> QueryComponentControl: ...
@overload
def message(name: Literal["QueryTime"], /, **fields: Any) -> QueryTime: ...
@overload
def message(name: Literal["ReportComponentAuthority"], /, **fields: Any) -> ReportComponentAuthority: ...
@overload
def message(name: Literal["ReportComponentStatus"], /, **fields: Any) -> ReportComponentStatus: ...
@overload
def message(name: Literal["ReportComponentControl"], /, **fields: Any) -> ReportComponentControl: ...
@overload
def message(name: Literal["ReportTime"], /, **fields: Any) -> ReportTime: ...
@overload
def message(name: Literal["ReportRefusal"], /, **fields: Any) -> ReportRefusal: ...
@overload
def message(name: Literal["QueryIdentification"], /, **fields: Any) -> QueryIdentification: ...
@overload
def message(name: Literal["QueryConfiguration"], /, **fields: Any) -> QueryConfiguration: ...
@overload
def message(name: Literal["QuerySubsystemList"], /, **fields: Any) -> QuerySubsystemList: ...
@overload
def message(name: Literal["QueryServices"], /, **fields: Any) -> QueryServices: ...
@overload
def message(name: Literal["ReportIdentification"], /, **fields: Any) -> ReportIdentification: ...
@overload
def message(name: Literal["ReportConfiguration"], /, **fields: Any) -> ReportConfiguration: ...
@overload
def message(name: Literal["ReportSubsystemList"], /, **fields: Any) -> ReportSubsystemList: ...
@overload
def message(name: Literal["ReportServices"], /, **fields: Any) -> ReportServices: ...
@overload
def message(name: Literal["SetCameraPose"], /, **fields: Any) -> SetCameraPose: ...
@overload
def message(name: Literal["SelectCamera"], /, **fields: Any) -> SelectCamera: ...
@overload
def message(name: Literal["SetCameraCapabilities"], /, **fields: Any) -> SetCameraCapabilities: ...
@overload
def message(name: Literal["SetCameraFormatOptions"], /, **fields: Any) -> SetCameraFormatOptions: ...
@overload
def message(name: Literal["QueryCameraPose"], /, **fields: Any) -> QueryCameraPose: ...
@overload
def message(name: Literal["QueryCameraCount"], /, **fields: Any) -> QueryCameraCount: ...
@overload
def message(name: Literal["QueryRelativeObjectPosition"], /, **fields: Any) -> QueryRelativeObjectPosition: ...
@overload
def message(name: Literal["QuerySelectedCamera"], /, **fields: Any) -> QuerySelectedCamera: ...
@overload
def message(name: Literal["QueryCameraCapabilities"], /, **fields: Any) -> QueryCameraCapabilities: ...
@overload
def message(name: Literal["QueryCameraFormatOptions"], /, **fields: Any) -> QueryCameraFormatOptions: ...
@overload
def message(name: Literal["QueryImage"], /, **fields: Any) -> QueryImage: ...
@overload
def message(name: Literal["QueryMap"], /, **fields: Any) -> QueryMap: ...
@overload
def message(name: Literal["ReportCameraPose"], /, **fields: Any) -> ReportCameraPose: ...
@overload
def message(name: Literal["ReportCameraCount"], /, **fields: Any) -> ReportCameraCount: ...
@overload
def message(name: Literal["ReportRelativeObjectPosition"], /, **fields: Any) -> ReportRelativeObjectPosition: ...
@overload
def message(name: Literal["ReportSelectedCamera"], /, **fields: Any) -> ReportSelectedCamera: ...
@overload
def message(name: Literal["ReportCameraCapabilities"], /, **fields: Any) -> ReportCameraCapabilities: ...
@overload
def message(name: Literal["ReportCameraFormatOptions"], /, **fields: Any) -> ReportCameraFormatOptions: ...
@overload
def message(name: Literal["ReportImage"], /, **fields: Any) -> ReportImage: ...
@overload
def message(name: Literal["ReportMap"], /, **fields: Any) -> ReportMap: ...
@overload
def message(name: Literal["CreateEvent"], /, **fields: Any) -> CreateEvent: ...
@overload
def message(name: Literal["UpdateEvent"], /, **fields: Any) -> UpdateEvent: ...
@overload
def message(name: Literal["CancelEvent"], /, **fields: Any) -> CancelEvent: ...
@overload
def message(name: Literal["ConfirmEventRequest"], /, **fields: Any) -> ConfirmEventRequest: ...
@overload
def message(name: Literal["RejectEventRequest"], /, **fields: Any) -> RejectEventRequest: ...
@overload
def message(name: Literal["QueryEvents"], /, **fields: Any) -> QueryEvents: ...
@overload
def message(name: Literal["ReportEvents"], /, **fields: Any) -> ReportEvents: ...
@overload
def message(name: Literal["Event"], /, **fields: Any) -> Event: ...
@overload
def message(name: Literal["SetJointEfforts"], /, **fields: Any) -> SetJointEfforts: ...
@overload
def message(name: Literal["SetJointPositions"], /, **fields: Any) -> SetJointPositions: ...
@overload
def message(name: Literal["SetJointVelocities"], /, **fields: Any) -> SetJointVelocities: ...
@overload
def message(name: Literal["SetToolPoint"], /, **fields: Any) -> SetToolPoint: ...
@overload
def message(name: Literal["SetEndEffectorPose"], /, **fields: Any) -> SetEndEffectorPose: ...
@overload
def message(name: Literal["SetEndEffectorVelocityState"], /, **fields: Any) -> SetEndEffectorVelocityState: ...
@overload
def message(name: Literal["SetEndEffectorPathMotion"], /, **fields: Any) -> SetEndEffectorPathMotion: ...
@overload
def message(name: Literal["QueryJointEfforts"], /, **fields: Any) -> QueryJointEfforts: ...
@overload
def message(name: Literal["QueryJointPositions"], /, **fields: Any) -> QueryJointPositions: ...
@overload
def message(name: Literal["QueryJointVelocities"], /, **fields: Any) -> QueryJointVelocities: ...
@overload
def message(name: Literal["QueryToolPoint"], /, **fields: Any) -> QueryToolPoint: ...
@overload
def message(name: Literal["QueryJointForceTorques"], /, **fields: Any) -> QueryJointForceTorques: ...
@overload
def message(name: Literal["ReportJointEfforts"], /, **fields: Any) -> ReportJointEfforts: ...
@overload
def message(name: Literal["ReportJointPositions"], /, **fields: Any) -> ReportJointPositions: ...
@overload
def message(name: Literal["ReportJointVelocities"], /, **fields: Any) -> ReportJointVelocities: ...
@overload
def message(name: Literal["ReportToolPoint"], /, **fields: Any) -> ReportToolPoint: ...
@overload
def message(name: Literal["ReportJointForceTorques"], /, **fields: Any) -> ReportJointForceTorques: ...
@overload
def message(name: Literal["SetJointMotion"], /, **fields: Any) -> SetJointMotion: ...
@overload
def message(name: Literal["QueryManipulatorSpecifications"], /, **fields: Any) -> QueryManipulatorSpecifications: ...
@overload
def message(name: Literal["ReportManipulatorSpecifications"], /, **fields: Any) -> ReportManipulatorSpecifications: ...
@overload
def message(name: Literal["SetPayloadDataElement"], /, **fields: Any) -> SetPayloadDataElement: ...
@overload
def message(name: Literal["QueryPayloadInterface"], /, **fields: Any) -> QueryPayloadInterface: ...
@overload
def message(name: Literal["QueryPayloadDataElement"], /, **fields: Any) -> QueryPayloadDataElement: ...
@overload
def message(name: Literal["ReportPayloadDataElement"], /, **fields: Any) -> ReportPayloadDataElement: ...
@overload
def message(name: Literal["ReportPayloadInterface"], /, **fields: Any) -> ReportPayloadInterface: ...
@overload
def message(name: Literal["RunMission"], /, **fields: Any) -> RunMission: ...
@overload
def message(name: Literal["AbortMission"], /, **fields: Any) -> AbortMission: ...
@overload
def message(name: Literal["PauseMission"], /, **fields: Any) -> PauseMission: ...
@overload
def message(name: Literal["ResumeMission"], /, **fields: Any) -> ResumeMission: ...
@overload
def message(name: Literal["RemoveMessages"], /, **fields: Any) -> RemoveMessages: ...
@overload
def message(name: Literal["ReplaceMessages"], /, **fields: Any) -> ReplaceMessages: ...
@overload
def message(name: Literal["QuerySpoolingPreference"], /, **fields: Any) -> QuerySpoolingPreference: ...
@overload
def message(name: Literal["QueryMissionStatus"], /, **fields: Any) -> QueryMissionStatus: ...
@overload
def message(name: Literal["ReportSpoolingPreference"], /, **fields: Any) -> ReportSpoolingPreference: ...
@overload
def message(name: Literal["ReportMissionStatus"], /, **fields: Any) -> ReportMissionStatus: ...
@overload
def message(name: Literal["SpoolMission"], /, **fields: Any) -> SpoolMission: ...
@overload
def message(name: Literal["SetVelocityState"], /, **fields: Any) -> SetVelocityState: ...
@overload
def message(name: Literal["SetWrenchEffort"], /, **fields: Any) -> SetWrenchEffort: ...
@overload
def message(name: Literal["SetDiscreteDevices"], /, **fields: Any) -> SetDiscreteDevices: ...
@overload
def message(name: Literal["SetGlobalVector"], /, **fields: Any) -> SetGlobalVector: ...
@overload
def message(name: Literal["SetLocalVector"], /, **fields: Any) -> SetLocalVector: ...
@overload
def message(name: Literal["SetTravelSpeed"], /, **fields: Any) -> SetTravelSpeed: ...
@overload
def message(name: Literal["SetGlobalWaypoint"], /, **fields: Any) -> SetGlobalWaypoint: ...
@overload
def message(name: Literal["SetLocalWaypoint"], /, **fields: Any) -> SetLocalWaypoint: ...
@overload
def message(name: Literal["SetGlobalPathSegment"], /, **fields: Any) -> SetGlobalPathSegment: ...
@overload
def message(name: Literal["SetLocalPathSegment"], /, **fields: Any) -> SetLocalPathSegment: ...
@overload
def message(name: Literal["QueryPlatformSpecifications"], /, **fields: Any) -> QueryPlatformSpecifications: ...
@overload
def message(name: Literal["QueryPlatformOperationalData"], /, **fields: Any) -> QueryPlatformOperationalData: ...
@overload
def message(name: Literal["QueryGlobalPose"], /, **fields: Any) -> QueryGlobalPose: ...
@overload
def message(name: Literal["QueryLocalPose"], /, **fields: Any) -> QueryLocalPose: ...
@overload
def message(name: Literal["QueryVelocityState"], /, **fields: Any) -> QueryVelocityState: ...
@overload
def message(name: Literal["QueryWrenchEffort"], /, **fields: Any) -> QueryWrenchEffort: ...
@overload
def message(name: Literal["QueryDiscreteDevices"], /, **fields: Any) -> QueryDiscreteDevices: ...
@overload
def message(name: Literal["QueryGlobalVector"], /, **fields: Any) -> QueryGlobalVector: ...
@overload
def message(name: Literal["QueryLocalVector"], /, **fields: Any) -> QueryLocalVector: ...
@overload
def message(name: Literal["QueryTravelSpeed"], /, **fields: Any) -> QueryTravelSpeed: ...
@overload
def message(name: Literal["QueryWaypointCount"], /, **fields: Any) -> QueryWaypointCount: ...
@overload
def message(name: Literal["QueryGlobalWaypoint"], /, **fields: Any) -> QueryGlobalWaypoint: ...
@overload
def message(name: Literal["QueryLocalWaypoint"], /, **fields: Any) -> QueryLocalWaypoint: ...
@overload
def message(name: Literal["QueryPathSegmentCount"], /, **fields: Any) -> QueryPathSegmentCount: ...
@overload
def message(name: Literal["QueryGlobalPathSegment"], /, **fields: Any) -> QueryGlobalPathSegment: ...
@overload
def message(name: Literal["QueryLocalPathSegment"], /, **fields: Any) -> QueryLocalPathSegment: ...
@overload
def message(name: Literal["ReportPlatformSpecifications"], /, **fields: Any) -> ReportPlatformSpecifications: ...
@overload
def message(name: Literal["ReportPlatformOperationalData"], /, **fields: Any) -> ReportPlatformOperationalData: ...
@overload
def message(name: Literal["ReportGlobalPose"], /, **fields: Any) -> ReportGlobalPose: ...
@overload
def message(name: Literal["ReportLocalPose"], /, **fields: Any) -> ReportLocalPose: ...
@overload
def message(name: Literal["ReportVelocityState"], /, **fields: Any) -> ReportVelocityState: ...
@overload
def message(name: Literal["ReportWrenchEffort"], /, **fields: Any) -> ReportWrenchEffort: ...
@overload
def message(name: Literal["ReportDiscreteDevices"], /, **fields: Any) -> ReportDiscreteDevices: ...
@overload
def message(name: Literal["ReportGlobalVector"], /, **fields: Any) -> ReportGlobalVector: ...
@overload
def message(name: Literal["ReportLocalVector"], /, **fields: Any) -> ReportLocalVector: ...
@overload
def message(name: Literal["ReportTravelSpeed"], /, **fields: Any) -> ReportTravelSpeed: ...
@overload
def message(name: Literal["ReportWaypointCount"], /, **fields: Any) -> ReportWaypointCount: ...
@overload
def message(name: Literal["ReportGlobalWaypoint"], /, **fields: Any) -> ReportGlobalWaypoint: ...
@overload
def message(name: Literal["ReportLocalWaypoint"], /, **fields: Any) -> ReportLocalWaypoint: ...
@overload
def message(name: Literal["ReportPathSegmentCount"], /, **fields: Any) -> ReportPathSegmentCount: ...
@overload
def message(name: Literal["ReportGlobalPathSegment"], /, **fields: Any) -> ReportGlobalPathSegment: ...
@overload
def message(name: Literal["ReportLocalPathSegment"], /, **fields: Any) -> ReportLocalPathSegment: ...
@overload
def message(name: Literal["SetVksFeatureClassMetadata"], /, **fields: Any) -> SetVksFeatureClassMetadata: ...
@overload
def message(name: Literal["TerminateVksDataTransfer"], /, **fields: Any) -> TerminateVksDataTransfer: ...
@overload
def message(name: Literal["QueryVksFeatureClassMetadata"], /, **fields: Any) -> QueryVksFeatureClassMetadata: ...
@overload
def message(name: Literal["QueryVksBounds"], /, **fields: Any) -> QueryVksBounds: ...
@overload
def message(name: Literal["ReportVksObjectsCreation"], /, **fields: Any) -> ReportVksObjectsCreation: ...
@overload
def message(name: Literal["ReportVksFeatureClassMetadata"], /, **fields: Any) -> ReportVksFeatureClassMetadata: ...
@overload
def message(name: Literal["ReportVksBounds"], /, **fields: Any) -> ReportVksBounds: ...
@overload
def message(name: Literal["ReportVksDataTransferTermination"], /, **fields: Any) -> ReportVksDataTransferTermination: ...
@overload
def message(name: Literal["CreateVksObjects"], /, **fields: Any) -> CreateVksObjects: ...
@overload
def message(name: Literal["DeleteVksObjects"], /, **fields: Any) -> DeleteVksObjects: ...
@overload
def message(name: Literal["QueryVksObjects"], /, **fields: Any) -> QueryVksObjects: ...
@overload
def message(name: Literal["ReportVksObjects"], /, **fields: Any) -> ReportVksObjects: ...
@overload
def message(name: str, /, **fields: Any) -> Message: ...

class Client(_Client):
    """A member of a JAUS system (see docs/python.md); `query` and `watch` are
    typed per query with the report that answers it."""

    @overload
    def query(self, dest: Address, message: QueryDataLinkStatus, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportDataLinkStatus: ...
    @overload
    def query(self, dest: Address, message: QuerySelectedDataLinkStatus, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportSelectedDataLinkStatus: ...
    @overload
    def query(self, dest: Address, message: QueryHeartbeatPulse, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportHeartbeatPulse: ...
    @overload
    def query(self, dest: Address, message: QueryComponentAuthority, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportComponentAuthority: ...
    @overload
    def query(self, dest: Address, message: QueryComponentStatus, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportComponentStatus: ...
    @overload
    def query(self, dest: Address, message: QueryComponentControl, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportComponentControl: ...
    @overload
    def query(self, dest: Address, message: QueryTime, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportTime: ...
    @overload
    def query(self, dest: Address, message: QueryIdentification, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportIdentification: ...
    @overload
    def query(self, dest: Address, message: QueryConfiguration, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportConfiguration: ...
    @overload
    def query(self, dest: Address, message: QuerySubsystemList, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportSubsystemList: ...
    @overload
    def query(self, dest: Address, message: QueryServices, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportServices: ...
    @overload
    def query(self, dest: Address, message: QueryCameraPose, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportCameraPose: ...
    @overload
    def query(self, dest: Address, message: QueryCameraCount, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportCameraCount: ...
    @overload
    def query(self, dest: Address, message: QueryRelativeObjectPosition, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportRelativeObjectPosition: ...
    @overload
    def query(self, dest: Address, message: QuerySelectedCamera, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportSelectedCamera: ...
    @overload
    def query(self, dest: Address, message: QueryCameraCapabilities, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportCameraCapabilities: ...
    @overload
    def query(self, dest: Address, message: QueryCameraFormatOptions, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportCameraFormatOptions: ...
    @overload
    def query(self, dest: Address, message: QueryImage, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportImage: ...
    @overload
    def query(self, dest: Address, message: QueryMap, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportMap: ...
    @overload
    def query(self, dest: Address, message: QueryEvents, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportEvents: ...
    @overload
    def query(self, dest: Address, message: QueryJointEfforts, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportJointEfforts: ...
    @overload
    def query(self, dest: Address, message: QueryJointPositions, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportJointPositions: ...
    @overload
    def query(self, dest: Address, message: QueryJointVelocities, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportJointVelocities: ...
    @overload
    def query(self, dest: Address, message: QueryToolPoint, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportToolPoint: ...
    @overload
    def query(self, dest: Address, message: QueryJointForceTorques, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportJointForceTorques: ...
    @overload
    def query(self, dest: Address, message: QueryManipulatorSpecifications, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportManipulatorSpecifications: ...
    @overload
    def query(self, dest: Address, message: QueryPayloadInterface, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportPayloadInterface: ...
    @overload
    def query(self, dest: Address, message: QueryPayloadDataElement, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportPayloadDataElement: ...
    @overload
    def query(self, dest: Address, message: QuerySpoolingPreference, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportSpoolingPreference: ...
    @overload
    def query(self, dest: Address, message: QueryMissionStatus, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportMissionStatus: ...
    @overload
    def query(self, dest: Address, message: QueryPlatformSpecifications, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportPlatformSpecifications: ...
    @overload
    def query(self, dest: Address, message: QueryPlatformOperationalData, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportPlatformOperationalData: ...
    @overload
    def query(self, dest: Address, message: QueryGlobalPose, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportGlobalPose: ...
    @overload
    def query(self, dest: Address, message: QueryLocalPose, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportLocalPose: ...
    @overload
    def query(self, dest: Address, message: QueryVelocityState, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportVelocityState: ...
    @overload
    def query(self, dest: Address, message: QueryWrenchEffort, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportWrenchEffort: ...
    @overload
    def query(self, dest: Address, message: QueryDiscreteDevices, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportDiscreteDevices: ...
    @overload
    def query(self, dest: Address, message: QueryGlobalVector, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportGlobalVector: ...
    @overload
    def query(self, dest: Address, message: QueryLocalVector, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportLocalVector: ...
    @overload
    def query(self, dest: Address, message: QueryTravelSpeed, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportTravelSpeed: ...
    @overload
    def query(self, dest: Address, message: QueryWaypointCount, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportWaypointCount: ...
    @overload
    def query(self, dest: Address, message: QueryGlobalWaypoint, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportGlobalWaypoint: ...
    @overload
    def query(self, dest: Address, message: QueryLocalWaypoint, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportLocalWaypoint: ...
    @overload
    def query(self, dest: Address, message: QueryPathSegmentCount, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportPathSegmentCount: ...
    @overload
    def query(self, dest: Address, message: QueryGlobalPathSegment, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportGlobalPathSegment: ...
    @overload
    def query(self, dest: Address, message: QueryLocalPathSegment, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportLocalPathSegment: ...
    @overload
    def query(self, dest: Address, message: QueryVksFeatureClassMetadata, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportVksFeatureClassMetadata: ...
    @overload
    def query(self, dest: Address, message: QueryVksBounds, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportVksBounds: ...
    @overload
    def query(self, dest: Address, message: QueryVksObjects, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> ReportVksObjects: ...
    @overload
    def query(self, dest: Address, message: Message, *, timeout: Optional[float] = ..., report: Optional[str] = ...) -> Message: ...
    @overload
    def watch(self, dest: Address, query: QueryDataLinkStatus, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportDataLinkStatus]: ...
    @overload
    def watch(self, dest: Address, query: QuerySelectedDataLinkStatus, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportSelectedDataLinkStatus]: ...
    @overload
    def watch(self, dest: Address, query: QueryHeartbeatPulse, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportHeartbeatPulse]: ...
    @overload
    def watch(self, dest: Address, query: QueryComponentAuthority, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportComponentAuthority]: ...
    @overload
    def watch(self, dest: Address, query: QueryComponentStatus, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportComponentStatus]: ...
    @overload
    def watch(self, dest: Address, query: QueryComponentControl, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportComponentControl]: ...
    @overload
    def watch(self, dest: Address, query: QueryTime, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportTime]: ...
    @overload
    def watch(self, dest: Address, query: QueryIdentification, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportIdentification]: ...
    @overload
    def watch(self, dest: Address, query: QueryConfiguration, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportConfiguration]: ...
    @overload
    def watch(self, dest: Address, query: QuerySubsystemList, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportSubsystemList]: ...
    @overload
    def watch(self, dest: Address, query: QueryServices, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportServices]: ...
    @overload
    def watch(self, dest: Address, query: QueryCameraPose, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportCameraPose]: ...
    @overload
    def watch(self, dest: Address, query: QueryCameraCount, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportCameraCount]: ...
    @overload
    def watch(self, dest: Address, query: QueryRelativeObjectPosition, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportRelativeObjectPosition]: ...
    @overload
    def watch(self, dest: Address, query: QuerySelectedCamera, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportSelectedCamera]: ...
    @overload
    def watch(self, dest: Address, query: QueryCameraCapabilities, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportCameraCapabilities]: ...
    @overload
    def watch(self, dest: Address, query: QueryCameraFormatOptions, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportCameraFormatOptions]: ...
    @overload
    def watch(self, dest: Address, query: QueryImage, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportImage]: ...
    @overload
    def watch(self, dest: Address, query: QueryMap, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportMap]: ...
    @overload
    def watch(self, dest: Address, query: QueryEvents, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportEvents]: ...
    @overload
    def watch(self, dest: Address, query: QueryJointEfforts, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportJointEfforts]: ...
    @overload
    def watch(self, dest: Address, query: QueryJointPositions, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportJointPositions]: ...
    @overload
    def watch(self, dest: Address, query: QueryJointVelocities, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportJointVelocities]: ...
    @overload
    def watch(self, dest: Address, query: QueryToolPoint, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportToolPoint]: ...
    @overload
    def watch(self, dest: Address, query: QueryJointForceTorques, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportJointForceTorques]: ...
    @overload
    def watch(self, dest: Address, query: QueryManipulatorSpecifications, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportManipulatorSpecifications]: ...
    @overload
    def watch(self, dest: Address, query: QueryPayloadInterface, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportPayloadInterface]: ...
    @overload
    def watch(self, dest: Address, query: QueryPayloadDataElement, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportPayloadDataElement]: ...
    @overload
    def watch(self, dest: Address, query: QuerySpoolingPreference, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportSpoolingPreference]: ...
    @overload
    def watch(self, dest: Address, query: QueryMissionStatus, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportMissionStatus]: ...
    @overload
    def watch(self, dest: Address, query: QueryPlatformSpecifications, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportPlatformSpecifications]: ...
    @overload
    def watch(self, dest: Address, query: QueryPlatformOperationalData, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportPlatformOperationalData]: ...
    @overload
    def watch(self, dest: Address, query: QueryGlobalPose, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportGlobalPose]: ...
    @overload
    def watch(self, dest: Address, query: QueryLocalPose, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportLocalPose]: ...
    @overload
    def watch(self, dest: Address, query: QueryVelocityState, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportVelocityState]: ...
    @overload
    def watch(self, dest: Address, query: QueryWrenchEffort, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportWrenchEffort]: ...
    @overload
    def watch(self, dest: Address, query: QueryDiscreteDevices, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportDiscreteDevices]: ...
    @overload
    def watch(self, dest: Address, query: QueryGlobalVector, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportGlobalVector]: ...
    @overload
    def watch(self, dest: Address, query: QueryLocalVector, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportLocalVector]: ...
    @overload
    def watch(self, dest: Address, query: QueryTravelSpeed, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportTravelSpeed]: ...
    @overload
    def watch(self, dest: Address, query: QueryWaypointCount, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportWaypointCount]: ...
    @overload
    def watch(self, dest: Address, query: QueryGlobalWaypoint, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportGlobalWaypoint]: ...
    @overload
    def watch(self, dest: Address, query: QueryLocalWaypoint, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportLocalWaypoint]: ...
    @overload
    def watch(self, dest: Address, query: QueryPathSegmentCount, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportPathSegmentCount]: ...
    @overload
    def watch(self, dest: Address, query: QueryGlobalPathSegment, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportGlobalPathSegment]: ...
    @overload
    def watch(self, dest: Address, query: QueryLocalPathSegment, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportLocalPathSegment]: ...
    @overload
    def watch(self, dest: Address, query: QueryVksFeatureClassMetadata, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportVksFeatureClassMetadata]: ...
    @overload
    def watch(self, dest: Address, query: QueryVksBounds, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportVksBounds]: ...
    @overload
    def watch(self, dest: Address, query: QueryVksObjects, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[ReportVksObjects]: ...
    @overload
    def watch(self, dest: Address, query: Message, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> Watch[Message]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryDataLinkStatus, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportDataLinkStatus]: ...
    @overload
    def watch_async(self, dest: Address, query: QuerySelectedDataLinkStatus, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportSelectedDataLinkStatus]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryHeartbeatPulse, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportHeartbeatPulse]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryComponentAuthority, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportComponentAuthority]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryComponentStatus, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportComponentStatus]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryComponentControl, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportComponentControl]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryTime, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportTime]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryIdentification, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportIdentification]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryConfiguration, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportConfiguration]: ...
    @overload
    def watch_async(self, dest: Address, query: QuerySubsystemList, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportSubsystemList]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryServices, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportServices]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryCameraPose, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportCameraPose]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryCameraCount, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportCameraCount]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryRelativeObjectPosition, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportRelativeObjectPosition]: ...
    @overload
    def watch_async(self, dest: Address, query: QuerySelectedCamera, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportSelectedCamera]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryCameraCapabilities, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportCameraCapabilities]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryCameraFormatOptions, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportCameraFormatOptions]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryImage, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportImage]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryMap, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportMap]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryEvents, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportEvents]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryJointEfforts, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportJointEfforts]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryJointPositions, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportJointPositions]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryJointVelocities, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportJointVelocities]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryToolPoint, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportToolPoint]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryJointForceTorques, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportJointForceTorques]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryManipulatorSpecifications, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportManipulatorSpecifications]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryPayloadInterface, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportPayloadInterface]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryPayloadDataElement, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportPayloadDataElement]: ...
    @overload
    def watch_async(self, dest: Address, query: QuerySpoolingPreference, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportSpoolingPreference]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryMissionStatus, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportMissionStatus]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryPlatformSpecifications, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportPlatformSpecifications]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryPlatformOperationalData, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportPlatformOperationalData]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryGlobalPose, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportGlobalPose]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryLocalPose, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportLocalPose]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryVelocityState, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportVelocityState]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryWrenchEffort, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportWrenchEffort]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryDiscreteDevices, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportDiscreteDevices]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryGlobalVector, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportGlobalVector]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryLocalVector, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportLocalVector]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryTravelSpeed, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportTravelSpeed]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryWaypointCount, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportWaypointCount]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryGlobalWaypoint, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportGlobalWaypoint]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryLocalWaypoint, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportLocalWaypoint]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryPathSegmentCount, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportPathSegmentCount]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryGlobalPathSegment, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportGlobalPathSegment]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryLocalPathSegment, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportLocalPathSegment]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryVksFeatureClassMetadata, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportVksFeatureClassMetadata]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryVksBounds, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportVksBounds]: ...
    @overload
    def watch_async(self, dest: Address, query: QueryVksObjects, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[ReportVksObjects]: ...
    @overload
    def watch_async(self, dest: Address, query: Message, *, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...) -> AsyncWatch[Message]: ...
