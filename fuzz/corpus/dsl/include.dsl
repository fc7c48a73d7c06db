/// Rows read from files: a file that is not there, a folder and a device are each refused at
/// their `include`, and the rest of the model is still read.
mod included {
    params { k = 1 }
    states { x }
    include "rows.dsl";
    include ".";
    include "/dev/zero";
    equations { der(x) = -k*x; }
}
