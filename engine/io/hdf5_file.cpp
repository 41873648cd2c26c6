#include "io/hdf5_file.hpp"

#include <algorithm>
#include <array>
#include <filesystem>
#include <functional>
#include <set>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <hdf5.h>
#include <unistd.h>

// Version-mapped calls (H5Oget_info*, H5Literate*, H5Ovisit*) are avoided on purpose: Debian maps
// them to the v18 signatures (dependencies notes §1.2) and 1.12 remaps them again. Everything here
// has one signature from 1.8 to 1.14, except two explicitly numbered calls in copyFileInto's
// attribute pass (object identity, VL memory release), chosen by H5_VERSION_GE.
static_assert(std::is_same_v<hid_t, std::int64_t>, "Hdf5File stores hid_t as std::int64_t");

namespace rupture::io {
namespace {

/// Owns one hid_t and closes it with the matching H5?close.
class Handle {
public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : m_id(id), m_closer(closer) {}
  Handle(Handle&& o) noexcept : m_id(std::exchange(o.m_id, -1)), m_closer(o.m_closer) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      m_id = std::exchange(o.m_id, -1);
      m_closer = o.m_closer;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  hid_t get() const { return m_id; }
  void reset() {
    if (m_id >= 0 && m_closer != nullptr) m_closer(m_id);
    m_id = -1;
  }

private:
  hid_t m_id = -1;
  Closer m_closer = nullptr;
};

// Error stacks and the automatic printer are per thread (notes §1.1), so silence the printer once
// in every thread that touches a file; failures are reported through Hdf5Error instead.
void silenceAutoPrint() {
  // Before the library's first use: no exit handler. HDF5 1.10's H5_term_library crashes on a file
  // whose close failed (see Hdf5File::close); every file we open is closed explicitly anyway.
  static const bool noExitHandler = [] { return H5dont_atexit() >= 0; }();
  (void)noExitHandler;
  thread_local bool silenced = false;
  if (!silenced) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    silenced = true;
  }
}

/// The innermost (most specific) message on this thread's error stack, e.g. the errno text.
std::string innermostHdf5Message() {
  std::string message;
  auto take = [](unsigned, const H5E_error2_t* err, void* data) -> herr_t {
    auto* out = static_cast<std::string*>(data);
    if (out->empty() && err != nullptr && err->desc != nullptr) {
      *out = std::string(err->func_name != nullptr ? err->func_name : "?") + ": " + err->desc;
    }
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, take, &message);
  H5Eclear2(H5E_DEFAULT);
  std::replace(message.begin(), message.end(), '\n', ' ');
  // The file drivers describe a failed system call with its buffer address, sizes and time; the
  // system's own words are what a reader needs ("... error message = 'No space left on device', ...").
  const std::string marker = "error message = '";
  if (const auto at = message.find(marker); at != std::string::npos) {
    const auto end = message.find('\'', at + marker.size());
    const auto colon = message.find(':');
    message = message.substr(0, colon == std::string::npos ? 0 : colon + 2) +
              message.substr(at + marker.size(), end == std::string::npos ? std::string::npos : end - at - marker.size());
  }
  return message;
}

[[noreturn]] void fail(const std::string& file, const std::string& obj, const std::string& what) {
  std::string msg = "HDF5: " + what + " (file '" + file + "'";
  if (!obj.empty()) msg += ", object '" + obj + "'";
  msg += ")";
  const std::string detail = innermostHdf5Message();
  if (!detail.empty()) msg += ": " + detail;
  throw Hdf5Error(msg);
}

hid_t checkId(hid_t id, const std::string& file, const std::string& obj, const std::string& what) {
  if (id < 0) fail(file, obj, what);
  return id;
}

void checkRc(herr_t rc, const std::string& file, const std::string& obj, const std::string& what) {
  if (rc < 0) fail(file, obj, what);
}

/// The names of an object's attributes, in `order`.
std::vector<std::string> attributeNames(hid_t obj, H5_index_t order, const std::string& file, const std::string& path) {
  std::vector<std::string> names;
  // A C callback must not let an exception escape: report it as an iteration failure instead.
  auto collect = [](hid_t, const char* attrName, const H5A_info_t*, void* data) -> herr_t {
    try {
      static_cast<std::vector<std::string>*>(data)->emplace_back(attrName);
      return 0;
    } catch (...) {
      return -1;
    }
  };
  checkRc(H5Aiterate2(obj, order, H5_ITER_INC, nullptr, collect, &names), file, path, "cannot list attributes");
  return names;
}

std::string attrLabel(const std::string& objPath, const std::string& name) {
  return objPath + "@" + name;
}

/// Link-creation list that makes missing parent groups, like `mkdir -p`.
Handle intermediateGroupsLcpl(const std::string& file, const std::string& obj) {
  Handle lcpl(checkId(H5Pcreate(H5P_LINK_CREATE), file, obj, "cannot create property list"),
              H5Pclose);
  checkRc(H5Pset_create_intermediate_group(lcpl.get(), 1), file, obj,
          "cannot enable intermediate groups");
  return lcpl;
}

/// File-access list for files we write: file format v2 or later, as H5MD recommends (notes §5.2).
Handle writerFapl(const std::string& file) {
  Handle fapl(checkId(H5Pcreate(H5P_FILE_ACCESS), file, "", "cannot create property list"),
              H5Pclose);
  checkRc(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_LATEST), file, "",
          "cannot set library version bounds");
  return fapl;
}

Handle variableUtf8String(const std::string& file, const std::string& obj) {
  Handle type(checkId(H5Tcopy(H5T_C_S1), file, obj, "cannot copy string type"), H5Tclose);
  checkRc(H5Tset_size(type.get(), H5T_VARIABLE), file, obj, "cannot make string type");
  checkRc(H5Tset_cset(type.get(), H5T_CSET_UTF8), file, obj, "cannot make string type");
  return type;
}

/// Writes one scalar attribute on an open object, replacing any attribute of that name.
void writeScalarAttribute(hid_t obj, const std::string& file, const std::string& label,
                          const std::string& name, hid_t fileType, hid_t memType,
                          const void* value) {
  const htri_t present = H5Aexists(obj, name.c_str());
  checkRc(present < 0 ? -1 : 0, file, label, "cannot query attribute");
  if (present > 0) checkRc(H5Adelete(obj, name.c_str()), file, label, "cannot replace attribute");
  Handle space(checkId(H5Screate(H5S_SCALAR), file, label, "cannot create dataspace"), H5Sclose);
  Handle attr(checkId(H5Acreate2(obj, name.c_str(), fileType, space.get(), H5P_DEFAULT,
                                 H5P_DEFAULT),
                      file, label, "cannot create attribute"),
              H5Aclose);
  checkRc(H5Awrite(attr.get(), memType, value), file, label, "cannot write attribute");
}

void writeStringAttribute(hid_t obj, const std::string& file, const std::string& label,
                          const std::string& name, const std::string& value) {
  Handle type = variableUtf8String(file, label);
  const char* text = value.c_str();
  writeScalarAttribute(obj, file, label, name, type.get(), type.get(), &text);
}

std::size_t product(const std::vector<std::size_t>& dims) {
  std::size_t n = 1;
  for (std::size_t d : dims) n *= d;
  return n;
}

// About 256 KiB per chunk: well inside the default 1 MiB chunk cache, large enough for deflate.
constexpr hsize_t kChunkTargetBytes = 256 * 1024;

/// Chunk shape: the full dataset, shrunk along the leading dimensions until it fits the target.
// Rows written between two calls of the hook (Hdf5File::setBetweenParts): about 4 MiB.
constexpr hsize_t kSlabBytes = hsize_t{4} << 20;

std::vector<hsize_t> chunkShape(const std::vector<hsize_t>& dims, std::size_t elementBytes) {
  std::vector<hsize_t> chunk(dims.size());
  for (std::size_t i = 0; i < dims.size(); ++i) chunk[i] = std::max<hsize_t>(dims[i], 1);
  auto bytes = [&] {
    hsize_t b = elementBytes;
    for (hsize_t c : chunk) b *= c;
    return b;
  };
  for (std::size_t i = 0; i < chunk.size() && bytes() > kChunkTargetBytes; ++i) {
    const hsize_t slice = bytes() / chunk[i];
    chunk[i] = std::max<hsize_t>(1, kChunkTargetBytes / slice);
  }
  return chunk;
}

/// Which numeric classes a typed read accepts.
enum class Accept { IntegerOrFloat, IntegerOnly };

void checkNumericClass(hid_t type, Accept accept, const std::string& file,
                       const std::string& label) {
  const H5T_class_t cls = H5Tget_class(type);
  checkRc(cls == H5T_NO_CLASS ? -1 : 0, file, label, "cannot query datatype");
  if (cls == H5T_INTEGER) return;
  if (cls == H5T_FLOAT && accept == Accept::IntegerOrFloat) return;
  fail(file, label,
       accept == Accept::IntegerOnly ? "not an integer type" : "not a numeric type");
}

/// The attribute `name` of the object at `objPath` (`label` names it in errors).
Handle openAttribute(hid_t file, const std::string& objPath, const std::string& name, const std::string& fileName,
                     const std::string& label) {
  return Handle(checkId(H5Aopen_by_name(file, objPath.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), fileName,
                        label, "cannot open attribute"),
                H5Aclose);
}

/// Reads a one-element numeric attribute into *out as memType.
void readScalarAttribute(hid_t file, const std::string& fileName, const std::string& objPath,
                         const std::string& name, hid_t memType, Accept accept, void* out) {
  const std::string label = attrLabel(objPath, name);
  const Handle attr = openAttribute(file, objPath, name, fileName, label);
  Handle type(checkId(H5Aget_type(attr.get()), fileName, label, "cannot get attribute type"),
              H5Tclose);
  checkNumericClass(type.get(), accept, fileName, label);
  Handle space(checkId(H5Aget_space(attr.get()), fileName, label, "cannot get dataspace"),
               H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1) {
    fail(fileName, label, "attribute is not a single value");
  }
  checkRc(H5Aread(attr.get(), memType, out), fileName, label, "cannot read attribute");
}

template <class T>
void writeTypedDataset(hid_t file, const std::string& fileName, const std::string& path,
                       const std::vector<T>& data, const std::vector<std::size_t>& dims,
                       const std::string& unit, hid_t fileType, hid_t memType,
                       const std::function<void()>& betweenParts, bool compress) {
  if (dims.empty()) fail(fileName, path, "dataset needs at least one dimension");
  if (product(dims) != data.size()) {
    fail(fileName, path,
         "dataset shape holds " + std::to_string(product(dims)) + " values but " +
             std::to_string(data.size()) + " were given");
  }
  // Replace an existing dataset, but never silently drop a group (and everything under it).
  const htri_t present = H5Lexists(file, path.c_str(), H5P_DEFAULT);
  if (present > 0) {
    Handle old(checkId(H5Oopen(file, path.c_str(), H5P_DEFAULT), fileName, path,
                       "cannot open existing object"),
               H5Oclose);
    if (H5Iget_type(old.get()) != H5I_DATASET) fail(fileName, path, "exists and is not a dataset");
    old.reset();
    checkRc(H5Ldelete(file, path.c_str(), H5P_DEFAULT), fileName, path,
            "cannot replace dataset");
  }

  const bool empty = data.empty();
  const std::vector<hsize_t> shape(dims.begin(), dims.end());
  // An empty dataset still needs a legal chunk shape (>= 1 per dim), hence unlimited max dims.
  std::vector<hsize_t> maxShape(shape.size(), H5S_UNLIMITED);
  if (!empty) maxShape.assign(dims.begin(), dims.end());
  Handle space(checkId(H5Screate_simple(static_cast<int>(shape.size()), shape.data(),
                                        maxShape.data()),
                       fileName, path, "cannot create dataspace"),
               H5Sclose);

  Handle dcpl(checkId(H5Pcreate(H5P_DATASET_CREATE), fileName, path,
                      "cannot create property list"),
              H5Pclose);
  const std::vector<hsize_t> chunk = chunkShape(shape, sizeof(T));
  checkRc(H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), fileName, path,
          "cannot set chunking");
  if (!empty && compress) {
    // Filter order matters: shuffle groups bytes of equal significance, then deflate squeezes.
    checkRc(H5Pset_shuffle(dcpl.get()), fileName, path, "cannot enable shuffle");
    checkRc(H5Pset_deflate(dcpl.get(), 4), fileName, path, "cannot enable deflate");
  }

  Handle lcpl = intermediateGroupsLcpl(fileName, path);
  Handle dset(checkId(H5Dcreate2(file, path.c_str(), fileType, space.get(), lcpl.get(),
                                 dcpl.get(), H5P_DEFAULT),
                      fileName, path, "cannot create dataset"),
              H5Dclose);
  if (!empty && !betweenParts) {
    checkRc(H5Dwrite(dset.get(), memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()), fileName,
            path, "cannot write dataset");
  } else if (!empty) {
    // In slabs of whole chunks along the first dimension, the hook between them: a dataset of
    // millions of rows takes a second or more to compress. The stored values are the same.
    hsize_t rowValues = 1;
    for (std::size_t i = 1; i < shape.size(); ++i) rowValues *= shape[i];
    const hsize_t slabRows = chunk[0] * std::max<hsize_t>(1, kSlabBytes / (chunk[0] * rowValues * sizeof(T)));
    for (hsize_t row = 0; row < shape[0]; row += slabRows) {
      betweenParts();
      std::vector<hsize_t> start(shape.size(), 0), count = shape;
      start[0] = row;
      count[0] = std::min(slabRows, shape[0] - row);
      Handle fileSpace(checkId(H5Dget_space(dset.get()), fileName, path, "cannot get dataspace"), H5Sclose);
      checkRc(H5Sselect_hyperslab(fileSpace.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
              fileName, path, "cannot select rows");
      Handle memSpace(checkId(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), fileName, path,
                              "cannot create dataspace"),
                      H5Sclose);
      checkRc(H5Dwrite(dset.get(), memType, memSpace.get(), fileSpace.get(), H5P_DEFAULT, data.data() + row * rowValues),
              fileName, path, "cannot write dataset");
    }
  }
  writeStringAttribute(dset.get(), fileName, attrLabel(path, "unit"), "unit", unit);
}

template <class T>
std::vector<T> readTypedDataset(hid_t file, const std::string& fileName, const std::string& path,
                                hid_t memType, Accept accept) {
  Handle dset(checkId(H5Dopen2(file, path.c_str(), H5P_DEFAULT), fileName, path,
                      "cannot open dataset"),
              H5Dclose);
  Handle type(checkId(H5Dget_type(dset.get()), fileName, path, "cannot get datatype"), H5Tclose);
  checkNumericClass(type.get(), accept, fileName, path);
  Handle space(checkId(H5Dget_space(dset.get()), fileName, path, "cannot get dataspace"),
               H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  checkRc(n < 0 ? -1 : 0, fileName, path, "cannot get dataset size");
  std::vector<T> out(static_cast<std::size_t>(n));
  if (!out.empty()) {
    checkRc(H5Dread(dset.get(), memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), fileName,
            path, "cannot read dataset");
  }
  return out;
}

}  // namespace

// ---- lifetime -----------------------------------------------------------------------------------

Hdf5File::Hdf5File(std::int64_t id, std::string path) : m_id(id), m_path(std::move(path)) {}

Hdf5File Hdf5File::create(const std::string& path) {
  silenceAutoPrint();
  Handle fapl = writerFapl(path);
  const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  return Hdf5File(checkId(id, path, "", "cannot create file"), path);
}

namespace {

/// A new file on HDF5's core (in-memory) driver: written to `path` on close when backingStore is
/// true, never written otherwise.
std::int64_t createOnCoreDriver(const std::string& path, bool backingStore) {
  silenceAutoPrint();
  Handle fapl = writerFapl(path);
  checkRc(H5Pset_fapl_core(fapl.get(), std::size_t{1} << 20, backingStore ? 1 : 0), path, "",
          "cannot select the in-memory driver");
  return checkId(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), path, "", "cannot create file");
}

}  // namespace

Hdf5File Hdf5File::createBuffered(const std::string& path) { return Hdf5File(createOnCoreDriver(path, true), path); }

Hdf5File Hdf5File::createInMemory(const std::string& name) { return Hdf5File(createOnCoreDriver(name, false), name); }

Hdf5File Hdf5File::openReadOnly(const std::string& path) {
  silenceAutoPrint();
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  return Hdf5File(checkId(id, path, "", "cannot open file read-only"), path);
}

Hdf5File Hdf5File::openReadWrite(const std::string& path) {
  silenceAutoPrint();
  Handle fapl = writerFapl(path);
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.get());
  return Hdf5File(checkId(id, path, "", "cannot open file read-write"), path);
}

Hdf5File::Hdf5File(Hdf5File&& other) noexcept
    : m_id(std::exchange(other.m_id, -1)), m_path(std::move(other.m_path)),
      m_betweenParts(std::move(other.m_betweenParts)), m_compress(other.m_compress) {}

Hdf5File& Hdf5File::operator=(Hdf5File&& other) noexcept {
  if (this != &other) {
    try {
      close();
    } catch (...) {  // noexcept: a failed close of the old file cannot be reported here
    }
    m_id = std::exchange(other.m_id, -1);
    m_path = std::move(other.m_path);
    m_betweenParts = std::move(other.m_betweenParts);
    m_compress = other.m_compress;
  }
  return *this;
}

Hdf5File::~Hdf5File() {
  try {
    close();
  } catch (...) {  // destructors must not throw; call close() explicitly to see the error
  }
}

void Hdf5File::close() {
  if (m_id < 0) return;
  silenceAutoPrint();
  const hid_t id = std::exchange(m_id, -1);  // closed (or unusable) from here on, even on failure
  // A failed flush (a full disk) leaves HDF5 1.10's metadata cache in a state where H5Fclose fails
  // too ("slist already enabled") and the id stays half-released. Nothing can make that file
  // consistent: give its blocks back (truncate through the driver's descriptor), leave the id to
  // the library (silenceAutoPrint switched off the exit handler that would crash on it), report.
  unsigned intent = 0;
  if (H5Fget_intent(id, &intent) >= 0 && (intent & H5F_ACC_RDWR) != 0 && H5Fflush(id, H5F_SCOPE_LOCAL) < 0) {
    const std::string detail = innermostHdf5Message();
    // Only the POSIX driver's handle is a descriptor (the core driver's points at its memory).
    const hid_t fapl = H5Fget_access_plist(id);
    const bool posix = fapl >= 0 && H5Pget_driver(fapl) == H5FD_SEC2;
    if (fapl >= 0) H5Pclose(fapl);
    void* handle = nullptr;
    if (posix && H5Fget_vfd_handle(id, H5P_DEFAULT, &handle) >= 0 && handle != nullptr)
      [[maybe_unused]] const int rc = ::ftruncate(*static_cast<int*>(handle), 0);
    if (H5Fclose(id) < 0) H5Eclear2(H5E_DEFAULT);
    throw Hdf5Error("HDF5: cannot write file '" + m_path + "' (its content is lost): " + detail);
  }
  checkRc(H5Fclose(id), m_path, "", "cannot close file");
}

void Hdf5File::flush() {
  requireOpen();
  checkRc(H5Fflush(m_id, H5F_SCOPE_LOCAL), m_path, "", "cannot flush file");
}

void Hdf5File::reopenReadWrite() {
  close();
  Hdf5File again = openReadWrite(m_path);
  m_id = std::exchange(again.m_id, -1);
}

const std::string& Hdf5File::path() const { return m_path; }

void Hdf5File::requireOpen() const {
  if (m_id < 0) throw Hdf5Error("HDF5: file '" + m_path + "' is closed");
  silenceAutoPrint();  // the file may have been moved to another thread since it was opened
}

// ---- groups and links ---------------------------------------------------------------------------

void Hdf5File::createGroup(const std::string& groupPath) {
  requireOpen();
  if (exists(groupPath)) {
    Handle obj(checkId(H5Oopen(m_id, groupPath.c_str(), H5P_DEFAULT), m_path, groupPath,
                       "cannot open object"),
               H5Oclose);
    if (H5Iget_type(obj.get()) != H5I_GROUP) fail(m_path, groupPath, "exists and is not a group");
    return;
  }
  Handle lcpl = intermediateGroupsLcpl(m_path, groupPath);
  Handle group(checkId(H5Gcreate2(m_id, groupPath.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
                       m_path, groupPath, "cannot create group"),
               H5Gclose);
}

bool Hdf5File::exists(const std::string& objPath) const {
  requireOpen();
  if (objPath.empty()) return false;
  // H5Lexists only looks at the last component, so walk the levels from the root down.
  std::string prefix;
  std::size_t start = 0;
  while (start < objPath.size()) {
    std::size_t end = objPath.find('/', start);
    if (end == std::string::npos) end = objPath.size();
    if (end > start) {
      prefix += '/';
      prefix.append(objPath, start, end - start);
      if (H5Lexists(m_id, prefix.c_str(), H5P_DEFAULT) <= 0) {
        H5Eclear2(H5E_DEFAULT);  // e.g. a dataset in the middle of the path: simply "no"
        return false;
      }
    }
    start = end + 1;
  }
  if (prefix.empty()) return true;  // "/" or "///": the root group
  // A dangling soft link exists as a link but cannot be opened.
  const htri_t resolves = H5Oexists_by_name(m_id, prefix.c_str(), H5P_DEFAULT);
  H5Eclear2(H5E_DEFAULT);
  return resolves > 0;
}

std::vector<std::string> Hdf5File::listGroup(const std::string& groupPath) const {
  requireOpen();
  Handle group(checkId(H5Gopen2(m_id, groupPath.c_str(), H5P_DEFAULT), m_path, groupPath,
                       "cannot open group"),
               H5Gclose);
  H5G_info_t info{};
  checkRc(H5Gget_info(group.get(), &info), m_path, groupPath, "cannot get group info");
  std::vector<std::string> names;
  names.reserve(info.nlinks);
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t len = H5Lget_name_by_idx(group.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i,
                                           nullptr, 0, H5P_DEFAULT);
    checkRc(len < 0 ? -1 : 0, m_path, groupPath, "cannot get link name");
    std::string name(static_cast<std::size_t>(len) + 1, '\0');
    checkRc(H5Lget_name_by_idx(group.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(),
                               name.size(), H5P_DEFAULT) < 0
                ? -1
                : 0,
            m_path, groupPath, "cannot get link name");
    name.resize(static_cast<std::size_t>(len));
    names.push_back(std::move(name));
  }
  // The name index is already in strcmp order; sorting keeps the promise whatever index is used.
  std::sort(names.begin(), names.end());
  return names;
}

namespace {

/// An object (group or dataset) of the file, closed when the handle goes.
Handle openObject(hid_t file, const std::string& filePath, const std::string& objPath) {
  return Handle(checkId(H5Oopen(file, objPath.c_str(), H5P_DEFAULT), filePath, objPath, "cannot open object"),
                H5Oclose);
}

}  // namespace

// ---- attributes ---------------------------------------------------------------------------------

void Hdf5File::setAttribute(const std::string& objPath, const std::string& name, double value) {
  requireOpen();
  const Handle obj = openObject(m_id, m_path, objPath);
  writeScalarAttribute(obj.get(), m_path, attrLabel(objPath, name), name, H5T_IEEE_F64LE,
                       H5T_NATIVE_DOUBLE, &value);
}

void Hdf5File::setAttribute(const std::string& objPath, const std::string& name,
                            std::int64_t value) {
  requireOpen();
  const Handle obj = openObject(m_id, m_path, objPath);
  writeScalarAttribute(obj.get(), m_path, attrLabel(objPath, name), name, H5T_STD_I64LE,
                       H5T_NATIVE_INT64, &value);
}

void Hdf5File::setAttribute(const std::string& objPath, const std::string& name,
                            const std::string& value) {
  requireOpen();
  const Handle obj = openObject(m_id, m_path, objPath);
  writeStringAttribute(obj.get(), m_path, attrLabel(objPath, name), name, value);
}

double Hdf5File::readAttributeDouble(const std::string& objPath, const std::string& name) const {
  requireOpen();
  double value = 0.0;
  readScalarAttribute(m_id, m_path, objPath, name, H5T_NATIVE_DOUBLE, Accept::IntegerOrFloat,
                      &value);
  return value;
}

std::int64_t Hdf5File::readAttributeInt(const std::string& objPath,
                                        const std::string& name) const {
  requireOpen();
  std::int64_t value = 0;
  readScalarAttribute(m_id, m_path, objPath, name, H5T_NATIVE_INT64, Accept::IntegerOnly, &value);
  return value;
}

std::string Hdf5File::readAttributeString(const std::string& objPath,
                                          const std::string& name) const {
  requireOpen();
  const std::string label = attrLabel(objPath, name);
  const Handle attr = openAttribute(m_id, objPath, name, m_path, label);
  Handle fileType(checkId(H5Aget_type(attr.get()), m_path, label, "cannot get attribute type"),
                  H5Tclose);
  if (H5Tget_class(fileType.get()) != H5T_STRING) fail(m_path, label, "not a string attribute");
  Handle space(checkId(H5Aget_space(attr.get()), m_path, label, "cannot get dataspace"),
               H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1) {
    fail(m_path, label, "attribute is not a single string");
  }

  const htri_t variable = H5Tis_variable_str(fileType.get());
  checkRc(variable < 0 ? -1 : 0, m_path, label, "cannot query string type");
  if (variable > 0) {
    // Same character set as stored: HDF5 does not convert between ASCII and UTF-8.
    Handle memType = variableUtf8String(m_path, label);
    checkRc(H5Tset_cset(memType.get(), H5Tget_cset(fileType.get())), m_path, label,
            "cannot make string type");
    char* text = nullptr;
    checkRc(H5Aread(attr.get(), memType.get(), &text), m_path, label, "cannot read attribute");
    std::string value = text != nullptr ? text : "";
    H5free_memory(text);  // allocated by the library for the variable-length read
    return value;
  }
  // Fixed length (e.g. H5MD's author name): read the raw bytes and cut the padding.
  const std::size_t size = H5Tget_size(fileType.get());
  checkRc(size == 0 ? -1 : 0, m_path, label, "cannot get string size");
  std::string value(size, '\0');
  checkRc(H5Aread(attr.get(), fileType.get(), value.data()), m_path, label,
          "cannot read attribute");
  if (const std::size_t nul = value.find('\0'); nul != std::string::npos) value.resize(nul);
  if (H5Tget_strpad(fileType.get()) == H5T_STR_SPACEPAD) {
    value.erase(value.find_last_not_of(' ') + 1);
  }
  return value;
}

bool Hdf5File::hasAttribute(const std::string& objPath, const std::string& name) const {
  requireOpen();
  const htri_t present = H5Aexists_by_name(m_id, objPath.c_str(), name.c_str(), H5P_DEFAULT);
  checkRc(present < 0 ? -1 : 0, m_path, attrLabel(objPath, name), "cannot query attribute");
  return present > 0;
}

std::vector<std::string> Hdf5File::listAttributes(const std::string& objPath) const {
  requireOpen();
  const Handle obj = openObject(m_id, m_path, objPath);
  std::vector<std::string> names = attributeNames(obj.get(), H5_INDEX_NAME, m_path, objPath);
  std::sort(names.begin(), names.end());
  return names;
}

// ---- datasets -----------------------------------------------------------------------------------

void Hdf5File::writeDataset(const std::string& path, const std::vector<double>& data,
                            const std::vector<std::size_t>& dims, const std::string& unit) {
  requireOpen();
  writeTypedDataset(m_id, m_path, path, data, dims, unit, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, m_betweenParts, m_compress);
}

void Hdf5File::writeDataset(const std::string& path, const std::vector<std::int32_t>& data,
                            const std::vector<std::size_t>& dims, const std::string& unit) {
  requireOpen();
  writeTypedDataset(m_id, m_path, path, data, dims, unit, H5T_STD_I32LE, H5T_NATIVE_INT32, m_betweenParts, m_compress);
}

void Hdf5File::writeDataset(const std::string& path, const std::vector<std::uint8_t>& data,
                            const std::vector<std::size_t>& dims, const std::string& unit) {
  requireOpen();
  writeTypedDataset(m_id, m_path, path, data, dims, unit, H5T_STD_U8LE, H5T_NATIVE_UINT8, m_betweenParts, m_compress);
}

void Hdf5File::writeDataset(const std::string& path, const std::vector<std::int64_t>& data,
                            const std::vector<std::size_t>& dims, const std::string& unit) {
  requireOpen();
  writeTypedDataset(m_id, m_path, path, data, dims, unit, H5T_STD_I64LE, H5T_NATIVE_INT64, m_betweenParts, m_compress);
}

void Hdf5File::remove(const std::string& objPath) {
  requireOpen();
  if (H5Lexists(m_id, objPath.c_str(), H5P_DEFAULT) <= 0) return;
  checkRc(H5Ldelete(m_id, objPath.c_str(), H5P_DEFAULT), m_path, objPath, "cannot remove");
}

void Hdf5File::writeDataset(const std::string& path, const std::vector<std::string>& data, const std::string& unit) {
  requireOpen();
  const htri_t present = H5Lexists(m_id, path.c_str(), H5P_DEFAULT);
  if (present > 0) {
    Handle old(checkId(H5Oopen(m_id, path.c_str(), H5P_DEFAULT), m_path, path, "cannot open existing object"),
               H5Oclose);
    if (H5Iget_type(old.get()) != H5I_DATASET) fail(m_path, path, "exists and is not a dataset");
    old.reset();
    checkRc(H5Ldelete(m_id, path.c_str(), H5P_DEFAULT), m_path, path, "cannot replace dataset");
  }
  Handle type = variableUtf8String(m_path, path);
  const hsize_t n = data.size();
  Handle space(checkId(H5Screate_simple(1, &n, nullptr), m_path, path, "cannot create dataspace"), H5Sclose);
  Handle lcpl = intermediateGroupsLcpl(m_path, path);
  Handle dset(checkId(H5Dcreate2(m_id, path.c_str(), type.get(), space.get(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
                      m_path, path, "cannot create dataset"),
              H5Dclose);
  std::vector<const char*> pointers;
  for (const std::string& text : data) pointers.push_back(text.c_str());
  if (!data.empty()) {
    checkRc(H5Dwrite(dset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()), m_path, path,
            "cannot write dataset");
  }
  writeStringAttribute(dset.get(), m_path, attrLabel(path, "unit"), "unit", unit);
}

std::vector<std::string> Hdf5File::readDatasetString(const std::string& path) const {
  requireOpen();
  Handle dset(checkId(H5Dopen2(m_id, path.c_str(), H5P_DEFAULT), m_path, path, "cannot open dataset"), H5Dclose);
  Handle fileType(checkId(H5Dget_type(dset.get()), m_path, path, "cannot get dataset type"), H5Tclose);
  if (H5Tget_class(fileType.get()) != H5T_STRING || H5Tis_variable_str(fileType.get()) <= 0)
    fail(m_path, path, "not a variable-length string dataset");
  Handle space(checkId(H5Dget_space(dset.get()), m_path, path, "cannot get dataspace"), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  checkRc(n < 0 ? -1 : 0, m_path, path, "cannot get dataspace size");
  std::vector<char*> pointers(static_cast<std::size_t>(n), nullptr);
  Handle memType = variableUtf8String(m_path, path);
  checkRc(H5Tset_cset(memType.get(), H5Tget_cset(fileType.get())), m_path, path, "cannot make string type");
  if (n > 0) {
    checkRc(H5Dread(dset.get(), memType.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()), m_path, path,
            "cannot read dataset");
  }
  std::vector<std::string> out;
  for (char* p : pointers) {
    out.emplace_back(p ? p : "");
    H5free_memory(p);  // allocated by the library for the variable-length read
  }
  return out;
}

std::vector<double> Hdf5File::readDatasetDouble(const std::string& path) const {
  requireOpen();
  return readTypedDataset<double>(m_id, m_path, path, H5T_NATIVE_DOUBLE, Accept::IntegerOrFloat);
}

std::vector<std::int64_t> Hdf5File::readDatasetInt(const std::string& path) const {
  requireOpen();
  return readTypedDataset<std::int64_t>(m_id, m_path, path, H5T_NATIVE_INT64,
                                        Accept::IntegerOnly);
}

std::vector<std::size_t> Hdf5File::datasetDims(const std::string& path) const {
  requireOpen();
  Handle dset(checkId(H5Dopen2(m_id, path.c_str(), H5P_DEFAULT), m_path, path,
                      "cannot open dataset"),
              H5Dclose);
  Handle space(checkId(H5Dget_space(dset.get()), m_path, path, "cannot get dataspace"), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  checkRc(rank < 0 ? -1 : 0, m_path, path, "cannot get rank");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  checkRc(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0 ? -1 : 0, m_path, path,
          "cannot get dimensions");
  return {dims.begin(), dims.end()};
}

// ---- merging ------------------------------------------------------------------------------------

namespace {

/// Identity of an object within its file: the attribute pass visits each copied object once, which
/// keeps objects shared by hard links (and hard-link cycles) from being walked again.
#if H5_VERSION_GE(1, 12, 0)
using ObjectKey = std::array<unsigned char, sizeof(H5O_token_t)>;
ObjectKey objectKey(hid_t obj, const std::string& file, const std::string& label) {
  H5O_info2_t info{};
  checkRc(H5Oget_info3(obj, &info, H5O_INFO_BASIC), file, label, "cannot get object info");
  ObjectKey key{};
  std::memcpy(key.data(), &info.token, key.size());
  return key;
}
#else
using ObjectKey = haddr_t;
ObjectKey objectKey(hid_t obj, const std::string& file, const std::string& label) {
  H5O_info_t info{};
  checkRc(H5Oget_info2(obj, &info, H5O_INFO_BASIC), file, label, "cannot get object info");
  return info.addr;
}
#endif

/// Releases the variable-length data (strings, sequences) that H5Aread allocated inside a buffer;
/// a no-op for fixed-size types.
class VlenRelease {
public:
  VlenRelease(hid_t memType, hid_t space, void* buffer)
      : m_type(memType), m_space(space), m_buffer(buffer) {}
  VlenRelease(const VlenRelease&) = delete;
  VlenRelease& operator=(const VlenRelease&) = delete;
  ~VlenRelease() {
#if H5_VERSION_GE(1, 12, 0)
    H5Treclaim(m_type, m_space, H5P_DEFAULT, m_buffer);
#else
    H5Dvlen_reclaim(m_type, m_space, H5P_DEFAULT, m_buffer);
#endif
  }

private:
  hid_t m_type;
  hid_t m_space;
  void* m_buffer;
};

std::string childPath(const std::string& parent, const std::string& name) {
  return parent == "/" ? "/" + name : parent + "/" + name;
}

/// The index that keeps the source's attribute order: creation order where the object tracks it.
H5_index_t attributeOrder(hid_t obj, const std::string& file, const std::string& label) {
  hid_t plist = -1;
  switch (H5Iget_type(obj)) {
    case H5I_GROUP: plist = H5Gget_create_plist(obj); break;
    case H5I_DATASET: plist = H5Dget_create_plist(obj); break;
    case H5I_DATATYPE: plist = H5Tget_create_plist(obj); break;
    default: return H5_INDEX_NAME;
  }
  Handle ocpl(checkId(plist, file, label, "cannot get creation properties"), H5Pclose);
  unsigned flags = 0;
  checkRc(H5Pget_attr_creation_order(ocpl.get(), &flags), file, label,
          "cannot get attribute creation order");
  return (flags & H5P_CRT_ORDER_TRACKED) != 0 ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME;
}

/// Re-creates every attribute of one object: read into memory as the native type, write back with
/// the stored type, same dataspace and creation properties (name encoding).
void copyAttributes(hid_t src, const std::string& srcFile, const std::string& srcPath, hid_t dst,
                    const std::string& dstFile, const std::string& dstPath) {
  const H5_index_t order = attributeOrder(src, srcFile, srcPath);
  const std::vector<std::string> names = attributeNames(src, order, srcFile, srcPath);

  for (const std::string& name : names) {
    const std::string from = attrLabel(srcPath, name);
    const std::string to = attrLabel(dstPath, name);
    Handle attr(checkId(H5Aopen(src, name.c_str(), H5P_DEFAULT), srcFile, from,
                        "cannot open attribute"),
                H5Aclose);
    Handle stored(checkId(H5Aget_type(attr.get()), srcFile, from, "cannot get attribute type"),
                  H5Tclose);
    const htri_t references = H5Tdetect_class(stored.get(), H5T_REFERENCE);
    checkRc(references < 0 ? -1 : 0, srcFile, from, "cannot query attribute type");
    if (references > 0) {
      fail(srcFile, from, "cannot copy an attribute holding references (they would point into "
                          "the source)");
    }
    // A transient copy: the source may use a named datatype, which belongs to the source file.
    Handle fileType(checkId(H5Tcopy(stored.get()), srcFile, from, "cannot copy attribute type"),
                    H5Tclose);
    Handle memType(checkId(H5Tget_native_type(stored.get(), H5T_DIR_ASCEND), srcFile, from,
                           "cannot get native attribute type"),
                   H5Tclose);
    Handle space(checkId(H5Aget_space(attr.get()), srcFile, from, "cannot get dataspace"),
                 H5Sclose);
    Handle acpl(checkId(H5Aget_create_plist(attr.get()), srcFile, from,
                        "cannot get attribute creation properties"),
                H5Pclose);
    const hssize_t points = H5Sget_simple_extent_npoints(space.get());
    const std::size_t size = H5Tget_size(memType.get());
    checkRc(points < 0 || size == 0 ? -1 : 0, srcFile, from, "cannot get attribute size");

    Handle copy(checkId(H5Acreate2(dst, name.c_str(), fileType.get(), space.get(), acpl.get(),
                                   H5P_DEFAULT),
                        dstFile, to, "cannot create attribute"),
                H5Aclose);
    if (points == 0) continue;  // an empty (null or zero-size) dataspace holds no data
    std::vector<unsigned char> buffer(static_cast<std::size_t>(points) * size);
    checkRc(H5Aread(attr.get(), memType.get(), buffer.data()), srcFile, from,
            "cannot read attribute");
    const VlenRelease release(memType.get(), space.get(), buffer.data());  // after the write
    checkRc(H5Awrite(copy.get(), memType.get(), buffer.data()), dstFile, to,
            "cannot write attribute");
  }
}

/// Attribute pass of copyFileInto: walks the source from `src` and the attribute-less copy from
/// `dst` side by side, link name by link name, copying the attributes of every object reached.
/// Soft and external links are followed in the source, as H5Ocopy expanded them.
class AttributeCopier {
public:
  AttributeCopier(std::string srcFile, std::string dstFile)
      : m_srcFile(std::move(srcFile)), m_dstFile(std::move(dstFile)) {}

  void object(hid_t src, const std::string& srcPath, hid_t dst, const std::string& dstPath) {
    if (!m_done.insert(objectKey(dst, m_dstFile, dstPath)).second) return;
    copyAttributes(src, m_srcFile, srcPath, dst, m_dstFile, dstPath);
    if (H5Iget_type(src) != H5I_GROUP) return;

    H5G_info_t info{};
    checkRc(H5Gget_info(src, &info), m_srcFile, srcPath, "cannot get group info");
    for (hsize_t i = 0; i < info.nlinks; ++i) {
      const ssize_t len = H5Lget_name_by_idx(src, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0,
                                             H5P_DEFAULT);
      checkRc(len < 0 ? -1 : 0, m_srcFile, srcPath, "cannot get link name");
      std::string name(static_cast<std::size_t>(len) + 1, '\0');
      checkRc(H5Lget_name_by_idx(src, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(),
                                 name.size(), H5P_DEFAULT) < 0
                  ? -1
                  : 0,
              m_srcFile, srcPath, "cannot get link name");
      name.resize(static_cast<std::size_t>(len));
      const std::string childSrc = childPath(srcPath, name);
      const std::string childDst = childPath(dstPath, name);
      // A dangling soft or external link has no object, hence no attributes; H5Ocopy kept it as
      // a link.
      const hid_t srcChild = H5Oopen(src, name.c_str(), H5P_DEFAULT);
      if (srcChild < 0) {
        H5Eclear2(H5E_DEFAULT);
        continue;
      }
      Handle from(srcChild, H5Oclose);
      Handle to(checkId(H5Oopen(dst, name.c_str(), H5P_DEFAULT), m_dstFile, childDst,
                        "cannot open copied object"),
                H5Oclose);
      object(from.get(), childSrc, to.get(), childDst);
    }
  }

private:
  std::string m_srcFile;
  std::string m_dstFile;
  std::set<ObjectKey> m_done;  ///< copied objects whose attributes are in place
};

}  // namespace

void Hdf5File::copyFileInto(const std::string& sourceFilePath, const std::string& groupPath) {
  requireOpen();
  const std::string destination = groupPath.empty() ? std::string("/") : groupPath;
  if (exists(destination)) fail(m_path, destination, "copy destination already exists");
  std::error_code ec;
  if (std::filesystem::equivalent(sourceFilePath, m_path, ec)) {
    fail(m_path, destination, "cannot copy a file into itself");
  }

  Handle source(checkId(H5Fopen(sourceFilePath.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                        sourceFilePath, "", "cannot open copy source read-only"),
                H5Fclose);
  Handle ocpypl(checkId(H5Pcreate(H5P_OBJECT_COPY), m_path, destination,
                        "cannot create property list"),
                H5Pclose);
  // Expand everything that could point outside the copied tree, so the merged file stands alone.
  // Attributes are left out here and re-created below: H5Ocopy of an object with more than 8
  // attributes (dense storage) including variable-length strings segfaults in Debian's 1.10.8.
  checkRc(H5Pset_copy_object(ocpypl.get(), H5O_COPY_WITHOUT_ATTR_FLAG |
                                               H5O_COPY_EXPAND_SOFT_LINK_FLAG |
                                               H5O_COPY_EXPAND_EXT_LINK_FLAG |
                                               H5O_COPY_EXPAND_REFERENCE_FLAG),
          m_path, destination, "cannot set copy flags");
  Handle lcpl = intermediateGroupsLcpl(m_path, destination);
  // Copying the source root in one call keeps objects hard-linked in the source shared.
  checkRc(H5Ocopy(source.get(), "/", m_id, destination.c_str(), ocpypl.get(), lcpl.get()), m_path,
          destination, "cannot copy '" + sourceFilePath + "'");

  try {
    Handle from(checkId(H5Oopen(source.get(), "/", H5P_DEFAULT), sourceFilePath, "/",
                        "cannot open object"),
                H5Oclose);
    Handle to(checkId(H5Oopen(m_id, destination.c_str(), H5P_DEFAULT), m_path, destination,
                      "cannot open copied object"),
              H5Oclose);
    AttributeCopier(sourceFilePath, m_path).object(from.get(), "/", to.get(), destination);
  } catch (...) {
    // Leave no half-copied group behind (the parents it created stay).
    H5Ldelete(m_id, destination.c_str(), H5P_DEFAULT);
    H5Eclear2(H5E_DEFAULT);
    throw;
  }
}

}  // namespace rupture::io
