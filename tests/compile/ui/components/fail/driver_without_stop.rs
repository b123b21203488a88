//! A driver must say how it stops: an empty implementation of a driver's trait does not
//! compile, and the error names the method to write.
use jaus::components::primitive_driver::PrimitiveDriver;

struct Motors;

impl PrimitiveDriver for Motors {}

fn main() {}
