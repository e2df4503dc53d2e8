// Loading the repository's OBJ and STL meshes (the robots' collision meshes,
// the test and config meshes): rbsim's own readers (loadMesh) beside assimp
// reading the same files into the same TriangleMesh (triangulated, welded
// by position as loadStl welds). It decided that assimp reads COLLADA only
// (docs/world_file.md, "Meshes"):
//
//   build/bench/bench_mesh_load --benchmark_min_time=1

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "meshio/mesh_io.h"
#include "meshio/vertex_welder.h"

namespace {

namespace fs = std::filesystem;

std::vector<std::string> meshFiles() {
  std::vector<std::string> files;
  for (const char* folder : {"bench/robots/data", "tests/data/meshes", "config/meshes"}) {
    const fs::path root = fs::path(RBSIM_SOURCE_DIR) / folder;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
      std::string extension = entry.path().extension().string();
      std::transform(extension.begin(), extension.end(), extension.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      // Only the files both read: the tests' deliberately broken ones are left out.
      if ((extension == ".obj" || extension == ".stl") && rbsim::loadMesh(entry.path().string())) {
        files.push_back(entry.path().string());
      }
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

const std::vector<std::string>& files() {
  static const std::vector<std::string> list = meshFiles();
  return list;
}

bool loadWithAssimp(const std::string& path, rbsim::TriangleMesh& mesh) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate);
  if (!scene || !scene->mRootNode) return false;
  mesh = {};
  rbsim::meshio::VertexWelder welder(mesh);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& part = *scene->mMeshes[m];
    for (unsigned f = 0; f < part.mNumFaces; ++f) {
      const aiFace& face = part.mFaces[f];
      if (face.mNumIndices != 3) continue;
      std::array<int, 3> triangle{};
      for (unsigned k = 0; k < 3; ++k) {
        const aiVector3D& v = part.mVertices[face.mIndices[k]];
        triangle[k] = welder.indexOf(rbsim::Vec3(v.x, v.y, v.z));
      }
      mesh.triangles.push_back(triangle);
    }
  }
  return true;
}

void countersFor(benchmark::State& state, long long triangles, long long bytes) {
  state.counters["files"] = static_cast<double>(files().size());
  state.counters["triangles"] = static_cast<double>(triangles);
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * bytes);
}

long long totalBytes() {
  long long bytes = 0;
  for (const std::string& path : files()) bytes += static_cast<long long>(fs::file_size(path));
  return bytes;
}

void HandWrittenReaders(benchmark::State& state) {
  long long triangles = 0;
  for (auto _ : state) {
    triangles = 0;
    for (const std::string& path : files()) {
      auto mesh = rbsim::loadMesh(path);
      triangles += static_cast<long long>(mesh->triangles.size());
      benchmark::DoNotOptimize(mesh);
    }
  }
  countersFor(state, triangles, totalBytes());
}
BENCHMARK(HandWrittenReaders)->Unit(benchmark::kMillisecond);

void Assimp(benchmark::State& state) {
  long long triangles = 0;
  int refused = 0;
  for (auto _ : state) {
    triangles = 0;
    refused = 0;
    for (const std::string& path : files()) {
      rbsim::TriangleMesh mesh;
      if (!loadWithAssimp(path, mesh)) ++refused;
      triangles += static_cast<long long>(mesh.triangles.size());
      benchmark::DoNotOptimize(mesh);
    }
  }
  countersFor(state, triangles, totalBytes());
  // Files rbsim reads and assimp refuses (tests/data/meshes/cube.obj's
  // four-coordinate vertex, for one).
  state.counters["refused"] = refused;
}
BENCHMARK(Assimp)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
