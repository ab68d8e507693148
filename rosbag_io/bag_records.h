#pragma once
// The records of a ROS1 bag checked before rosbag_storage opens it. That library trusts every
// length and offset in the file (a record's header and data lengths, a chunk's uncompressed size,
// the offsets of index entries into a chunk): a damaged bag makes it read past its buffers or
// allocate up to 4 GB. checkBagRecords walks the records as rosbag::Bag reads them: the file
// header, the connection and chunk info records at the index position, each chunk with its index
// records, and every indexed message record inside its (decompressed) chunk.
#include <string>

namespace rpvio {

/// InputError(path, "byte N" or "chunk at byte N, offset M") on the first record that does not
/// fit, on a format other than 2.0, an encrypted or unindexed bag, or a chunk above 1 GiB.
/// Reads the whole bag and decompresses every chunk once.
void checkBagRecords(const std::string& path);

}  // namespace rpvio
