#pragma once
// Result files: a small move-only RAII wrapper over one HDF5 file, on the HDF5 C API only.
// The C API is the part of HDF5 that is thread-safe in Debian's build (dependencies notes §1.1),
// so several threads may each use their own Hdf5File at once. One Hdf5File must not be used by
// two threads at the same time. hdf5.h stays out of this header: hid_t is int64_t in 1.10,
// checked by a static_assert in the .cpp.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace rupture::io {

/// Thrown for any HDF5 failure; the message names the file and the object path, and carries the
/// innermost message of the HDF5 error stack.
class Hdf5Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// One open HDF5 file. Paths inside the file are absolute ("/a/b"; "/" is the root group).
class Hdf5File {
public:
  /// Creates (truncating) a file. New objects use file format v2 and later (H5MD recommends it).
  static Hdf5File create(const std::string& path);
  /// Creates (truncating) a file that HDF5 builds in memory (its core driver) and writes to `path`
  /// only when closed, in one pass: a disk that fills up fails that write (close() throws), never
  /// an object copy half way through.
  static Hdf5File createBuffered(const std::string& path);
  /// A file held in memory only and never written (HDF5's core driver without a backing store):
  /// `name` only names it in error messages.
  static Hdf5File createInMemory(const std::string& name);
  static Hdf5File openReadOnly(const std::string& path);
  static Hdf5File openReadWrite(const std::string& path);

  Hdf5File(Hdf5File&& other) noexcept;
  Hdf5File& operator=(Hdf5File&& other) noexcept;
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;
  ~Hdf5File();  ///< closes; never throws

  /// Idempotent. Every other call on a closed file throws Hdf5Error.
  void close();
  /// False once closed, or after a close that failed (a full disk: see close()).
  bool isOpen() const { return m_id >= 0; }
  void flush();
  /// Opens the same path again for writing, after close() (the file was whole on disk in between:
  /// it may have been copied) or closing it first; keeps this object's settings (compression, the
  /// between-parts hook).
  void reopenReadWrite();
  const std::string& path() const;

  /// Creates the group and any missing parents; does nothing if it is already a group.
  void createGroup(const std::string& groupPath);
  /// True when every level of objPath is a link and the last one resolves to an object.
  bool exists(const std::string& objPath) const;
  /// Names of the group's direct children, sorted.
  std::vector<std::string> listGroup(const std::string& groupPath) const;

  /// Scalar attributes on the group or dataset at objPath ("/" for the root). An existing
  /// attribute of that name is replaced, whatever its type. Strings are variable-length UTF-8.
  /// (An int literal is ambiguous between the numeric overloads: write 1.0 or std::int64_t{1}.)
  void setAttribute(const std::string& objPath, const std::string& name, double value);
  void setAttribute(const std::string& objPath, const std::string& name, std::int64_t value);
  void setAttribute(const std::string& objPath, const std::string& name, const std::string& value);
  /// Reads any integer or floating-point attribute as double.
  double readAttributeDouble(const std::string& objPath, const std::string& name) const;
  /// Reads an integer attribute; a floating-point one throws rather than being truncated.
  std::int64_t readAttributeInt(const std::string& objPath, const std::string& name) const;
  /// Reads a variable- or fixed-length string attribute.
  std::string readAttributeString(const std::string& objPath, const std::string& name) const;
  /// Throws if objPath itself does not exist.
  bool hasAttribute(const std::string& objPath, const std::string& name) const;
  /// Attribute names, sorted.
  std::vector<std::string> listAttributes(const std::string& objPath) const;

  /// Writes a row-major dataset of shape dims (rank >= 1, product == data.size()), creating missing
  /// parent groups and replacing an existing dataset at path. Non-empty datasets are chunked with
  /// shuffle + deflate(4); empty ones are chunked with unlimited max dims, which keeps a zero-size
  /// shape legal. `unit` goes into the string attribute "unit" (SI, "1" for dimensionless).
  void writeDataset(const std::string& path, const std::vector<double>& data,
                    const std::vector<std::size_t>& dims, const std::string& unit);
  void writeDataset(const std::string& path, const std::vector<std::int32_t>& data,
                    const std::vector<std::size_t>& dims, const std::string& unit);
  void writeDataset(const std::string& path, const std::vector<std::uint8_t>& data,
                    const std::vector<std::size_t>& dims, const std::string& unit);
  void writeDataset(const std::string& path, const std::vector<std::int64_t>& data,
                    const std::vector<std::size_t>& dims, const std::string& unit);
  /// Off: numeric datasets written from now on are stored as they are (no shuffle, no deflate), for
  /// files written often and read once (checkpoints). On by default.
  void setCompression(bool on) { m_compress = on; }
  /// Removes the link at objPath (a dataset or a whole group) if it exists; the space stays in the file.
  void remove(const std::string& objPath);
  /// Called between the slabs (about 4 MiB each) in which numeric datasets are then written, and
  /// before the first: it may throw to abandon a long write (a cancelled run's snapshot), which
  /// leaves that dataset partly written. Empty (the default): each dataset in one write.
  void setBetweenParts(std::function<void()> hook) { m_betweenParts = std::move(hook); }
  /// A 1-D dataset of variable-length UTF-8 strings (text columns of a table), contiguous, with
  /// the string attribute "unit" ("" for text); replaces an existing dataset at path.
  void writeDataset(const std::string& path, const std::vector<std::string>& data, const std::string& unit);
  /// Reads a 1-D dataset of variable-length strings.
  std::vector<std::string> readDatasetString(const std::string& path) const;
  /// Reads any integer or floating-point dataset, flattened row-major, converted to double.
  std::vector<double> readDatasetDouble(const std::string& path) const;
  /// Reads any integer dataset as int64; a floating-point one throws rather than being truncated.
  std::vector<std::int64_t> readDatasetInt(const std::string& path) const;
  /// Current shape ({} for a scalar dataset).
  std::vector<std::size_t> datasetDims(const std::string& path) const;

  /// Deep-copies the whole root group of another file (which should be closed everywhere else)
  /// to groupPath of this file: every child with all its attributes, and the source's root
  /// attributes as attributes of groupPath. groupPath must not exist yet (missing parents are
  /// created). Soft and external links and object references in datasets are expanded into
  /// copies, so the result never points at the source (a dangling link stays a dangling link).
  /// Objects hard-linked in the source stay shared in the copy.
  /// Objects are copied by one H5Ocopy without attributes, then every attribute of every group,
  /// dataset and named datatype is re-created through memory: H5Ocopy of attributes segfaults in
  /// Debian's HDF5 1.10.8 on an object with more than 8 attributes including variable-length
  /// strings, such as the engine's /summary group. An attribute holding references cannot be
  /// re-pointed and throws. On any failure after the copy started, groupPath is removed again.
  void copyFileInto(const std::string& sourceFilePath, const std::string& groupPath);

private:
  Hdf5File(std::int64_t id, std::string path);
  void requireOpen() const;

  std::int64_t m_id = -1;  ///< hid_t of the open file, -1 once closed
  std::string m_path;
  std::function<void()> m_betweenParts;
  bool m_compress = true;
};

}  // namespace rupture::io
