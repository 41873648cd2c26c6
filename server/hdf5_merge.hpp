#pragma once
// Deep copy of a closed HDF5 run file into a group of another file, on the HDF5 C API.
//
// Why not H5Ocopy alone (rupture::io::Hdf5File::copyFileInto): in Debian's HDF5 1.10.8, H5Ocopy
// of an object whose attributes are in dense storage (more than 8 attributes) and include
// variable-length strings segfaults inside H5T__conv_vlen, and the engine's /summary group is such
// an object. So objects are copied without attributes (H5O_COPY_WITHOUT_ATTR_FLAG, soft and
// external links expanded), then every attribute is read into memory and written again.
#include <string>

namespace rupture::server {

/// Copies every object of the file at `sourcePath` under `groupPath` (which must not exist; its
/// parents are created) in the open file `destinationFile` (an hid_t), with all attributes, the
/// source root's attributes going onto groupPath. Hard links shared in the source stay shared.
/// Throws std::runtime_error naming the file and object on failure.
void copyRunFileInto(long long destinationFile, const std::string& sourcePath, const std::string& groupPath);

}  // namespace rupture::server
