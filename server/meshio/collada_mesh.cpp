#include "meshio/collada_mesh.h"

#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Core>
#include <Eigen/LU>

#include <array>
#include <cctype>
#include <exception>
#include <new>
#include <utility>
#include <vector>

#include "meshio/collada_guard.h"
#include "meshio/mesh_file.h"
#include "meshio/mesh_io.h"
#include "meshio/vertex_welder.h"

namespace rbsim {
namespace {

using meshio::fileError;

// Every file assimp asks for is refused: the document itself comes from
// memory, and the files a COLLADA document may name (images, external
// references) could point anywhere on the host.
class NoFiles final : public Assimp::IOSystem {
 public:
  bool Exists(const char* /*file*/) const override { return false; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* /*file*/, const char* /*mode*/) override { return nullptr; }
  void Close(Assimp::IOStream* stream) override { delete stream; }
};

// assimp's reason, fit for a message: it names the in-memory document by a
// placeholder, which is replaced by nothing (the message starts with the
// path), and it may quote bytes of the file.
std::string assimpReason(const char* text) {
  std::string reason = text && *text ? text : "no reason given";
  for (const std::string& placeholder :
       {std::string(AI_MEMORYIO_MAGIC_FILENAME) + ".dae", std::string(AI_MEMORYIO_MAGIC_FILENAME)}) {
    for (size_t at = reason.find(placeholder); at != std::string::npos;
         at = reason.find(placeholder)) {
      reason.replace(at, placeholder.size(), "the file");
    }
  }
  constexpr size_t kMaxShown = 300;
  std::string shown;
  for (size_t i = 0; i < reason.size() && i < kMaxShown; ++i) {
    const auto c = static_cast<unsigned char>(reason[i]);
    shown += std::isprint(c) ? static_cast<char>(c) : '?';
  }
  if (reason.size() > kMaxShown) shown += "...";
  return shown;
}

Expected<std::string> readWholeFile(const std::string& path) {
  Expected<meshio::OpenFile> file = meshio::openMeshFile(path);
  if (!file) return file.error();
  if (file->size > kMaxColladaBytes) {
    return fileError(path, "is " + std::to_string(file->size) + " bytes; COLLADA files over " +
                               std::to_string(kMaxColladaBytes) +
                               " bytes are rejected (mesh files are untrusted input)");
  }
  std::string text(static_cast<size_t>(file->size), '\0');
  file->stream.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (file->stream.gcount() != static_cast<std::streamsize>(text.size())) {
    return fileError(path, "read error");
  }
  return text;
}

Eigen::Matrix4d toEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d result;
  for (unsigned row = 0; row < 4; ++row) {
    for (unsigned column = 0; column < 4; ++column) {
      result(row, column) = static_cast<double>(m[row][column]);
    }
  }
  return result;
}

// From the file's units and up axis to metres and Z-up.
Eigen::Matrix4d sceneToWorld(const meshio::ColladaAsset& asset) {
  Eigen::Matrix3d rotation;
  switch (asset.up) {
    case meshio::UpAxis::kZ:
      rotation.setIdentity();
      break;
    case meshio::UpAxis::kY:  // +90 degrees about X: the file's +Y becomes +Z
      rotation << 1, 0, 0, 0, 0, -1, 0, 1, 0;
      break;
    case meshio::UpAxis::kX:  // the file's +X becomes +Z (and +Y becomes -X)
      rotation << 0, -1, 0, 0, 0, -1, 1, 0, 0;
      break;
  }
  Eigen::Matrix4d result = Eigen::Matrix4d::Identity();
  result.topLeftCorner<3, 3>() = asset.metresPerUnit * rotation;
  return result;
}

struct MeshInstance {
  const aiMesh* mesh = nullptr;
  Eigen::Matrix4d transform;  // mesh to world
};

// Every mesh the node tree instances, with its node's transform. The root
// node's own transform is assimp's unit scale (its up-axis rotation is off);
// `rootTransform` replaces it.
Expected<std::vector<MeshInstance>> meshInstances(const aiScene& scene,
                                                  const Eigen::Matrix4d& rootTransform,
                                                  const std::string& path) {
  std::vector<MeshInstance> instances;
  std::vector<std::pair<const aiNode*, Eigen::Matrix4d>> pending{{scene.mRootNode, rootTransform}};
  while (!pending.empty()) {
    const auto [node, transform] = pending.back();
    pending.pop_back();
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      if (node->mMeshes[i] >= scene.mNumMeshes) {
        return fileError(path, "assimp gave a node that refers to a mesh it does not have");
      }
      instances.push_back({scene.mMeshes[node->mMeshes[i]], transform});
    }
    for (unsigned i = 0; i < node->mNumChildren; ++i) {
      const aiNode* child = node->mChildren[i];
      pending.emplace_back(child, transform * toEigen(child->mTransformation));
    }
  }
  return instances;
}

}  // namespace

Expected<TriangleMesh> loadCollada(const std::string& path) {
  Expected<std::string> text = readWholeFile(path);
  if (!text) return text.error();
  Expected<meshio::ColladaAsset> asset = meshio::checkColladaDocument(*text, path);
  if (!asset) return asset.error();

  Assimp::Importer importer;  // assimp's default logger is the null logger: nothing is printed
  importer.SetIOHandler(new NoFiles);  // the importer owns it
  // The unit and up axis are applied below, from the values checked above.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // A file with bones but no mesh would otherwise get a made-up one.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  // Triangulate: polygons become triangles (lines and points stay as they
  // are and are skipped). aiProcess_JoinIdenticalVertices is not used: it
  // joins only vertices whose normals and texture coordinates match too,
  // which leaves a flat-shaded cube open; welding by position does it below.
  constexpr unsigned kSteps = aiProcess_Triangulate | aiProcess_ValidateDataStructure;
  const aiScene* scene = nullptr;
  try {
    // The hint makes the COLLADA importer the only one tried.
    scene = importer.ReadFileFromMemory(text->data(), text->size(), kSteps, "dae");
  } catch (const std::bad_alloc&) {
    return fileError(path, "COLLADA file could not be read: out of memory");
  } catch (const std::exception& e) {
    return fileError(path, "COLLADA file could not be read: " + assimpReason(e.what()));
  }
  if (!scene || !scene->mRootNode) {
    return fileError(path,
                     "COLLADA file could not be read: " + assimpReason(importer.GetErrorString()));
  }
  text->clear();
  text->shrink_to_fit();

  Expected<std::vector<MeshInstance>> instances =
      meshInstances(*scene, sceneToWorld(*asset), path);
  if (!instances) return instances.error();
  // The triangle limit, before anything is stored: node instancing lets a
  // small file place one mesh many times.
  long long triangles = 0;
  for (const MeshInstance& instance : *instances) {
    for (unsigned f = 0; f < instance.mesh->mNumFaces; ++f) {
      if (instance.mesh->mFaces[f].mNumIndices == 3) ++triangles;
    }
    if (triangles > kMaxMeshTriangles) return fileError(path, meshio::triangleLimitText());
  }
  if (triangles == 0) {
    return fileError(path, "COLLADA file has no triangles in its visual scene");
  }

  TriangleMesh mesh;
  mesh.triangles.reserve(static_cast<size_t>(triangles));
  meshio::VertexWelder welder(mesh);
  for (const MeshInstance& instance : *instances) {
    const aiMesh& part = *instance.mesh;
    const Eigen::Matrix3d linear = instance.transform.topLeftCorner<3, 3>();
    const Vec3 offset = instance.transform.topRightCorner<3, 1>();
    const bool mirrors = linear.determinant() < 0.0;
    for (unsigned f = 0; f < part.mNumFaces; ++f) {
      const aiFace& face = part.mFaces[f];
      if (face.mNumIndices != 3) continue;
      std::array<int, 3> triangle{};
      for (unsigned corner = 0; corner < 3; ++corner) {
        const unsigned index = face.mIndices[corner];
        if (index >= part.mNumVertices) {
          return fileError(path, "assimp gave a face that refers to a vertex it does not have");
        }
        const aiVector3D& v = part.mVertices[index];
        const Vec3 p = linear * Vec3(static_cast<double>(v.x), static_cast<double>(v.y),
                                     static_cast<double>(v.z)) +
                       offset;
        if (!p.allFinite()) {
          return fileError(path, "mesh '" + assimpReason(part.mName.C_Str()) +
                                     "' has a vertex that is not finite once placed by its node");
        }
        triangle[corner] = welder.indexOf(p);
      }
      if (mirrors) std::swap(triangle[1], triangle[2]);
      mesh.triangles.push_back(triangle);
    }
  }
  return mesh;
}

}  // namespace rbsim
