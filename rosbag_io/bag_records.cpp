#include "rosbag_io/bag_records.h"

#include <bzlib.h>
#include <rosbag/constants.h>
#include <roslz4/lz4s.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <vector>

#include "common/input_error.h"
#include "common/input_file.h"

namespace rpvio {
namespace {

constexpr uint64_t kMaxChunkBytes = uint64_t{1} << 30;
constexpr uint64_t kMaxHeaderBytes = uint64_t{16} << 20;
const std::string kVersionLine = "#ROSBAG V2.0\n";

using Fields = std::map<std::string, std::string>;

template <typename T>
T as(const char* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof value);
  return value;
}

/// Bytes read in order from the bag file or from a chunk's content, every length checked against
/// what is left; errors name the position.
class Reader {
 public:
  Reader(std::ifstream& file, uint64_t size, const std::string& path)
      : path_(path), file_(&file), size_(size) {}
  /// The content of the chunk whose record starts at byte `chunk_at` of the file.
  Reader(const char* content, uint64_t size, uint64_t chunk_at, const std::string& path)
      : path_(path), content_(content), size_(size), chunk_at_(chunk_at) {}

  uint64_t pos() const { return pos_; }

  [[noreturn]] void fail(const std::string& reason, uint64_t at) const {
    throw InputError(
        path_,
        (file_ ? "byte " : "chunk at byte " + std::to_string(chunk_at_) + ", offset ") +
            std::to_string(at),
        reason);
  }

  void seek(uint64_t pos, const std::string& what) {
    if (pos > size_) fail(what + " beyond the end (" + std::to_string(size_) + " bytes)", pos);
    pos_ = pos;
  }

  std::string bytes(uint64_t n, const std::string& what) {
    if (n > size_ - pos_)
      fail(what + " of " + std::to_string(n) + " bytes runs past the end", pos_);
    std::string out(n, '\0');
    if (file_) {
      file_->seekg(static_cast<std::streamoff>(pos_));
      if (!file_->read(out.data(), static_cast<std::streamsize>(n))) fail("cannot be read", pos_);
    } else {
      std::memcpy(out.data(), content_ + pos_, n);
    }
    pos_ += n;
    return out;
  }

  uint32_t u32(const std::string& what) { return as<uint32_t>(bytes(4, what).data()); }

  /// `length` bytes of fields, each a 4-byte length then "name=value" (ros::Header's layout).
  Fields fields(uint64_t length, const std::string& what) {
    const uint64_t start = pos_;
    if (length > kMaxHeaderBytes) fail(what + " of " + std::to_string(length) + " bytes", start);
    const std::string block = bytes(length, what);
    Fields out;
    for (size_t i = 0; i < block.size();) {
      if (block.size() - i < 4) fail(what + ": a field's length is cut", start + i);
      const uint32_t n = as<uint32_t>(block.data() + i);
      if (n > block.size() - i - 4) fail(what + ": a field runs past its end", start + i);
      const std::string field = block.substr(i + 4, n);
      const size_t equals = field.find('=');
      if (equals == std::string::npos) fail(what + ": a field without '='", start + i);
      out[field.substr(0, equals)] = field.substr(equals + 1);
      i += 4 + n;
    }
    return out;
  }

 private:
  std::string path_;
  std::ifstream* file_ = nullptr;
  const char* content_ = nullptr;
  uint64_t size_, pos_ = 0, chunk_at_ = 0;
};

/// A record's header fields and data length (the reader is then at its data).
struct Record {
  uint64_t at;
  Fields header;
  uint32_t data_length;
};

Record anyRecord(Reader& r, const std::string& what) {
  Record record;
  record.at = r.pos();
  record.header = r.fields(r.u32(what + " header length"), what + " header");
  record.data_length = r.u32(what + " data length");
  return record;
}

template <typename T>
T number(const Reader& r, const Record& record, const std::string& name, const std::string& what) {
  const auto field = record.header.find(name);
  if (field == record.header.end() || field->second.size() != sizeof(T))
    r.fail(what + " without a " + std::to_string(sizeof(T)) + "-byte " + name + " field",
           record.at);
  return as<T>(field->second.data());
}

/// The next record, InputError unless its op is `op`.
Record record(Reader& r, uint8_t op, const std::string& what) {
  Record record = anyRecord(r, what);
  if (number<uint8_t>(r, record, rosbag::OP_FIELD_NAME, what) != op)
    r.fail("not a " + what + " record", record.at);
  return record;
}

/// The records rosbag reads at an index entry's offset into a chunk: connection and message
/// definition records (their data not skipped, as rosbag::Bag does) up to the message's data.
void checkMessageAt(Reader& chunk, uint32_t offset) {
  chunk.seek(offset, "a message (index entry)");
  for (;;) {
    const Record r = anyRecord(chunk, "message");
    const uint8_t op = number<uint8_t>(chunk, r, rosbag::OP_FIELD_NAME, "message");
    if (op == rosbag::OP_MSG_DATA) {
      chunk.seek(chunk.pos() + r.data_length, "message data");
      return;
    }
    if (op != rosbag::OP_MSG_DEF && op != rosbag::OP_CONNECTION)
      chunk.fail("not a message record", r.at);
  }
}

/// A chunk's content: its data as it is, or decompressed to exactly the size it says.
std::unique_ptr<char[]> chunkContent(Reader& file, const Record& chunk, uint64_t& size) {
  const auto compression = chunk.header.find(rosbag::COMPRESSION_FIELD_NAME);
  if (compression == chunk.header.end()) file.fail("chunk without a compression", chunk.at);
  const bool raw = compression->second == rosbag::COMPRESSION_NONE;
  size = raw ? chunk.data_length : number<uint32_t>(file, chunk, rosbag::SIZE_FIELD_NAME, "chunk");
  if (chunk.data_length > kMaxChunkBytes || size > kMaxChunkBytes)
    file.fail("chunk of more than 1 GiB", chunk.at);
  std::string data = file.bytes(chunk.data_length, "chunk data");
  std::unique_ptr<char[]> content(new char[size]);  // uninitialised: pages touched as written
  if (raw) {
    std::memcpy(content.get(), data.data(), size);
    return content;
  }
  unsigned int out = static_cast<unsigned int>(size);
  bool ok;
  if (compression->second == rosbag::COMPRESSION_LZ4)
    ok = roslz4_buffToBuffDecompress(data.data(), chunk.data_length, content.get(), &out) ==
         ROSLZ4_OK;
  else if (compression->second == rosbag::COMPRESSION_BZ2)
    ok = BZ2_bzBuffToBuffDecompress(content.get(), &out, data.data(), chunk.data_length, 0, 0) ==
         BZ_OK;
  else
    file.fail("unknown chunk compression '" + compression->second + "'", chunk.at);
  if (!ok || out != size)
    file.fail(compression->second + " chunk that does not decompress to its " +
                  std::to_string(size) + " bytes",
              chunk.at);
  return content;
}

}  // namespace

void checkBagRecords(const std::string& path) {
  std::ifstream in = openInputFile(path, "bag");
  const uint64_t file_size = std::filesystem::file_size(path);
  Reader file(in, file_size, path);
  if (file.bytes(std::min<uint64_t>(file_size, kVersionLine.size()), "version line") !=
      kVersionLine)
    file.fail("not a ROS bag of format 2.0 (no '#ROSBAG V2.0' line)", 0);
  const Record header = record(file, rosbag::OP_FILE_HEADER, "file header");
  if (const auto e = header.header.find(rosbag::ENCRYPTOR_FIELD_NAME);
      e != header.header.end() && !e->second.empty())
    file.fail("encrypted bags are not supported", header.at);
  const auto index_pos = number<uint64_t>(file, header, rosbag::INDEX_POS_FIELD_NAME, "header");
  if (index_pos == 0) file.fail("the bag is not indexed (rosbag reindex)", header.at);
  const auto connection_count =
      number<uint32_t>(file, header, rosbag::CONNECTION_COUNT_FIELD_NAME, "header");
  const auto chunk_count = number<uint32_t>(file, header, rosbag::CHUNK_COUNT_FIELD_NAME, "header");

  file.seek(index_pos, "the index");
  std::set<uint32_t> connections;
  for (uint32_t i = 0; i < connection_count; ++i) {
    const Record connection = record(file, rosbag::OP_CONNECTION, "connection");
    connections.insert(
        number<uint32_t>(file, connection, rosbag::CONNECTION_FIELD_NAME, "connection"));
    file.fields(connection.data_length, "connection header");
  }
  struct Chunk {
    uint64_t pos;
    size_t indexes;  // one index record per connection in the chunk
  };
  std::vector<Chunk> chunks;
  for (uint32_t i = 0; i < chunk_count; ++i) {
    const Record info = record(file, rosbag::OP_CHUNK_INFO, "chunk info");
    const uint64_t count = number<uint32_t>(file, info, rosbag::COUNT_FIELD_NAME, "chunk info");
    const std::string entries = file.bytes(count * 8, "chunk info");
    std::set<uint32_t> ids;
    for (uint64_t k = 0; k < count; ++k) ids.insert(as<uint32_t>(entries.data() + 8 * k));
    chunks.push_back(
        {number<uint64_t>(file, info, rosbag::CHUNK_POS_FIELD_NAME, "chunk info"), ids.size()});
  }

  for (const Chunk& chunk : chunks) {
    // rosbag::Bag takes a chunk at 0 for the one it has decompressed (none yet: an empty buffer).
    if (chunk.pos < kVersionLine.size()) file.fail("a chunk inside the version line", chunk.pos);
    file.seek(chunk.pos, "a chunk");
    const Record record_of_chunk = record(file, rosbag::OP_CHUNK, "chunk");
    uint64_t size;
    const std::unique_ptr<char[]> content = chunkContent(file, record_of_chunk, size);
    Reader in_chunk(content.get(), size, chunk.pos, path);
    for (size_t k = 0; k < chunk.indexes; ++k) {
      const Record index = record(file, rosbag::OP_INDEX_DATA, "index");
      const auto connection = number<uint32_t>(file, index, rosbag::CONNECTION_FIELD_NAME, "index");
      if (!connections.count(connection))
        file.fail("index of the unknown connection " + std::to_string(connection), index.at);
      const uint64_t count = number<uint32_t>(file, index, rosbag::COUNT_FIELD_NAME, "index");
      const uint64_t entries_at = file.pos();
      const std::string entries = file.bytes(count * 12, "index entries");
      for (uint64_t e = 0; e < count; ++e) {
        const char* entry = entries.data() + 12 * e;
        // ros::Time carries whole seconds of nanoseconds over, and throws beyond 32 bits.
        if (as<uint32_t>(entry) + uint64_t{as<uint32_t>(entry + 4)} / 1000000000 >
            std::numeric_limits<uint32_t>::max())
          file.fail("index entry time out of range", entries_at + 12 * e);
        checkMessageAt(in_chunk, as<uint32_t>(entry + 8));
      }
    }
  }
}

}  // namespace rpvio
