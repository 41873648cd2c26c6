#include "hdf5_merge.hpp"

#include <stdexcept>
#include <vector>

#include <hdf5.h>

namespace rupture::server {
namespace {

static_assert(sizeof(hid_t) == sizeof(long long), "hid_t is a 64-bit integer in HDF5 1.10");

/// Closes an HDF5 identifier with the matching H5*close at scope exit.
class Id {
public:
  Id(hid_t id, herr_t (*closer)(hid_t)) : m_id(id), m_closer(closer) {}
  ~Id() {
    if (m_id >= 0) m_closer(m_id);
  }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  hid_t get() const { return m_id; }
  bool valid() const { return m_id >= 0; }

private:
  hid_t m_id;
  herr_t (*m_closer)(hid_t);
};

[[noreturn]] void fail(const std::string& what) { throw std::runtime_error("merging results: " + what); }

hid_t check(hid_t id, const std::string& what) {
  if (id < 0) fail(what);
  return id;
}

/// Copies every attribute of `src` onto `dst` (replacing same-named ones), through memory.
void copyAttributes(hid_t src, hid_t dst, const std::string& where) {
  struct Context {
    hid_t dst;
    const std::string* where;
    std::string error;
  } ctx{dst, &where, {}};
  auto op = [](hid_t loc, const char* name, const H5A_info_t*, void* data) -> herr_t {
    auto* c = static_cast<Context*>(data);
    Id attr(H5Aopen(loc, name, H5P_DEFAULT), H5Aclose);
    Id fileType(H5Aget_type(attr.get()), H5Tclose);
    Id space(H5Aget_space(attr.get()), H5Sclose);
    if (!attr.valid() || !fileType.valid() || !space.valid()) {
      c->error = "cannot open attribute '" + std::string(name) + "' of " + *c->where;
      return -1;
    }
    Id memType(H5Tget_native_type(fileType.get(), H5T_DIR_ASCEND), H5Tclose);
    const hssize_t points = H5Sget_simple_extent_npoints(space.get());
    const size_t size = memType.valid() ? H5Tget_size(memType.get()) : 0;
    if (!memType.valid() || points < 0 || size == 0) {
      c->error = "unsupported attribute '" + std::string(name) + "' of " + *c->where;
      return -1;
    }
    std::vector<unsigned char> buffer(static_cast<size_t>(points) * size + 1);
    if (H5Aread(attr.get(), memType.get(), buffer.data()) < 0) {
      c->error = "cannot read attribute '" + std::string(name) + "' of " + *c->where;
      return -1;
    }
    const bool variable = H5Tdetect_class(memType.get(), H5T_VLEN) > 0 ||
                          (H5Tget_class(memType.get()) == H5T_STRING && H5Tis_variable_str(memType.get()) > 0);
    herr_t rc = 0;
    if (H5Aexists(c->dst, name) > 0) H5Adelete(c->dst, name);
    {
      Id copy(H5Acreate2(c->dst, name, fileType.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
      rc = copy.valid() ? H5Awrite(copy.get(), memType.get(), buffer.data()) : -1;
    }
    if (variable) H5Dvlen_reclaim(memType.get(), space.get(), H5P_DEFAULT, buffer.data());
    if (rc < 0) {
      c->error = "cannot write attribute '" + std::string(name) + "' of " + *c->where;
      return -1;
    }
    return 0;
  };
  hsize_t index = 0;
  if (H5Aiterate2(src, H5_INDEX_NAME, H5_ITER_INC, &index, op, &ctx) < 0) {
    fail(ctx.error.empty() ? "cannot copy the attributes of " + where : ctx.error);
  }
}

}  // namespace

void copyRunFileInto(long long destinationFile, const std::string& sourcePath, const std::string& groupPath) {
  const hid_t dst = static_cast<hid_t>(destinationFile);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // per thread: errors become exceptions, not stderr noise
  Id source(H5Fopen(sourcePath.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!source.valid()) fail("cannot open " + sourcePath);
  Id copyProps(check(H5Pcreate(H5P_OBJECT_COPY), "property list"), H5Pclose);
  H5Pset_copy_object(copyProps.get(),
                     H5O_COPY_WITHOUT_ATTR_FLAG | H5O_COPY_EXPAND_SOFT_LINK_FLAG | H5O_COPY_EXPAND_EXT_LINK_FLAG);
  Id linkProps(check(H5Pcreate(H5P_LINK_CREATE), "property list"), H5Pclose);
  H5Pset_create_intermediate_group(linkProps.get(), 1);
  if (H5Ocopy(source.get(), "/", dst, groupPath.c_str(), copyProps.get(), linkProps.get()) < 0) {
    fail("cannot copy " + sourcePath + " to " + groupPath);
  }

  // Attributes: the root's onto the group, then every object reached by a hard or soft link.
  {
    Id from(check(H5Oopen(source.get(), "/", H5P_DEFAULT), "cannot open / of " + sourcePath), H5Oclose);
    Id to(check(H5Oopen(dst, groupPath.c_str(), H5P_DEFAULT), "cannot open " + groupPath), H5Oclose);
    copyAttributes(from.get(), to.get(), sourcePath + ":/");
  }
  struct Walk {
    hid_t dst;
    const std::string* group;
    const std::string* sourcePath;
    std::string error;
  } walk{dst, &groupPath, &sourcePath, {}};
  auto visit = [](hid_t root, const char* name, const H5L_info_t* info, void* data) -> herr_t {
    auto* w = static_cast<Walk*>(data);
    if (info->type != H5L_TYPE_HARD && info->type != H5L_TYPE_SOFT) return 0;  // external: expanded, no attributes
    const std::string target = *w->group + "/" + name;
    try {
      Id from(check(H5Oopen(root, name, H5P_DEFAULT), std::string("cannot open ") + name), H5Oclose);
      Id to(check(H5Oopen(w->dst, target.c_str(), H5P_DEFAULT), "cannot open " + target), H5Oclose);
      copyAttributes(from.get(), to.get(), *w->sourcePath + ":/" + name);
    } catch (const std::exception& e) {
      w->error = e.what();
      return -1;
    }
    return 0;
  };
  if (H5Lvisit(source.get(), H5_INDEX_NAME, H5_ITER_INC, visit, &walk) < 0) {
    fail(walk.error.empty() ? "cannot walk " + sourcePath : walk.error);
  }
}

}  // namespace rupture::server
