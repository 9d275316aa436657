#include "MeshImport.h"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

namespace daep::world {
namespace {

Eigen::Affine3d toEigen(const aiMatrix4x4& m) {
    Eigen::Matrix4d e;
    e << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
        m.d4;
    return Eigen::Affine3d(e);
}

void appendMesh(const aiMesh& mesh, const Eigen::Affine3d& transform, TriangleMesh& out) {
    const int base = static_cast<int>(out.vertices.size());
    for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
        const aiVector3D& v = mesh.mVertices[i];
        out.vertices.push_back((transform * Eigen::Vector3d(v.x, v.y, v.z)).cast<float>());
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices != 3)
            continue;  // points and lines have no surface
        out.triangles.emplace_back(base + static_cast<int>(face.mIndices[0]),
                                   base + static_cast<int>(face.mIndices[1]),
                                   base + static_cast<int>(face.mIndices[2]));
    }
}

void appendNode(const aiScene& scene, const aiNode& node, const Eigen::Affine3d& parent,
                TriangleMesh& out) {
    const Eigen::Affine3d transform = parent * toEigen(node.mTransformation);
    for (unsigned i = 0; i < node.mNumMeshes; ++i)
        appendMesh(*scene.mMeshes[node.mMeshes[i]], transform, out);
    for (unsigned i = 0; i < node.mNumChildren; ++i)
        appendNode(scene, *node.mChildren[i], transform, out);
}

}  // namespace

bool importMesh(const std::string& file, const Eigen::Affine3d& transform, TriangleMesh& out,
                std::string& error) {
    Assimp::Importer importer;
    // The simulator is z-up like Gazebo: keep COLLADA files in their authored axes instead of
    // assimp's y-up conversion. Units (<unit meter=...>) are still applied.
    importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
    const aiScene* scene =
        importer.ReadFile(file, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
    if (scene == nullptr || scene->mRootNode == nullptr) {
        error = importer.GetErrorString();
        if (error.empty())
            error = "assimp could not read it";
        return false;
    }
    appendNode(*scene, *scene->mRootNode, transform, out);
    return true;
}

}  // namespace daep::world
