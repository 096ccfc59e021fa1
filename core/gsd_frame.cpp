#include "core/gsd_frame.hpp"
#include "core/units.hpp"
#include <cmath>

namespace terrace {

std::vector<std::string> hoomdChunkNames() {
    return {"configuration/step",
            "configuration/box",
            "particles/N",
            "particles/types",
            "particles/typeid",
            "particles/mass",
            "particles/moment_inertia",
            "particles/type_shapes",
            "particles/position",
            "particles/image",
            "particles/orientation",
            "particles/velocity",
            "particles/angmom",
            "log/time_ps"};
}

nlohmann::json gsdTypeShape(const Scene& scene) {
    const auto& p = scene.potential;
    if (p.kind == "lj") return {{"type", "Sphere"}, {"diameter", p.sigma}};
    if (p.kind == "gay-berne")
        return {{"type", "Ellipsoid"},
                {"a", p.sigma / 2},
                {"b", p.sigma / 2},
                {"c", p.kappa * p.sigma / 2}};
    if (p.kind == "sites") {
        nlohmann::json centres = nlohmann::json::array(), diameters = nlohmann::json::array();
        for (const auto& s : scene.body.sites) {
            centres.push_back({s.r.x(), s.r.y(), s.r.z()});
            diameters.push_back(s.sigma);
        }
        return {{"type", "SphereUnion"}, {"centers", centres}, {"diameters", diameters}};
    }
    // rod-lj
    return {{"type", "ConvexPolyhedron"},
            {"rounding_radius", p.sigma / 2},
            {"vertices", {{0.0, 0.0, -p.zeta / 2}, {0.0, 0.0, p.zeta / 2}}}};
}

GsdBodyType gsdBodyType(const Scene& scene) {
    GsdBodyType t;
    const auto& k = scene.potential.kind;
    t.name = k == "lj"          ? "sphere"
             : k == "gay-berne" ? "ellipsoid"
             : k == "sites"     ? "molecule"
                                : "rod";
    t.shape = gsdTypeShape(scene);
    t.mass = scene.body.mass;
    t.inertia = scene.body.kind == "sphere" ? Vec3::Zero() : scene.body.inertia;
    return t;
}

namespace {

template <class T>
void chunk(GsdWriter& f, const char* name, GsdType type, std::uint64_t n, std::uint32_t m,
           const std::vector<T>& data) {
    f.writeChunk(name, type, n, m, data.data());
}

/// Rows of NUL-padded strings, as GSD stores type names and shapes.
std::vector<std::int8_t> stringRows(const std::vector<std::string>& rows, std::uint32_t& width) {
    width = 1;
    for (const auto& r : rows)
        width = std::max<std::uint32_t>(width, std::uint32_t(r.size()) + 1);
    std::vector<std::int8_t> out(rows.size() * width, 0);
    for (std::size_t k = 0; k < rows.size(); ++k)
        for (std::size_t c = 0; c < rows[k].size(); ++c)
            out[k * width + c] = static_cast<std::int8_t>(rows[k][c]);
    return out;
}

void writeConstantChunks(GsdWriter& f, const Snapshot& s, const GsdBodyType& type) {
    const auto n = static_cast<std::uint32_t>(s.size());
    const float L = float(s.boxLength);
    chunk(f, "configuration/box", GsdType::Float, 6, 1, std::vector<float>{L, L, L, 0, 0, 0});
    chunk(f, "particles/N", GsdType::UInt32, 1, 1, std::vector<std::uint32_t>{n});
    std::uint32_t width = 0;
    const auto names = stringRows({type.name}, width);
    chunk(f, "particles/types", GsdType::Int8, 1, width, names);
    chunk(f, "particles/typeid", GsdType::UInt32, n, 1, std::vector<std::uint32_t>(n, 0));
    chunk(f, "particles/mass", GsdType::Float, n, 1, std::vector<float>(n, float(type.mass)));
    std::vector<float> inertia;
    inertia.reserve(3 * n);
    for (std::uint32_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
            inertia.push_back(float(type.inertia[c]));
    chunk(f, "particles/moment_inertia", GsdType::Float, n, 3, inertia);
    const auto shapes = stringRows({type.shape.dump()}, width);
    chunk(f, "particles/type_shapes", GsdType::Int8, 1, width, shapes);
}

} // namespace

void writeHoomdFrame(GsdWriter& f, const Snapshot& s, const GsdBodyType& type,
                     std::uint64_t sample) {
    const std::uint64_t n = std::uint64_t(s.size());
    if (f.frames() == 0) writeConstantChunks(f, s, type);
    chunk(f, "configuration/step", GsdType::UInt64, 1, 1, std::vector<std::uint64_t>{sample});
    const double L = s.boxLength, perPs = 1.0 / units::psPerTimeUnit;
    std::vector<float> position, orientation, velocity, angmom;
    std::vector<std::int32_t> image;
    position.reserve(3 * n), image.reserve(3 * n), velocity.reserve(3 * n);
    orientation.reserve(4 * n), angmom.reserve(4 * n);
    for (std::uint64_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) {
            // HOOMD's box spans [-L/2, L/2); our unwrapped positions are taken into it.
            const double x = s.position[i][c];
            const double k = std::floor(x / L + 0.5);
            double w = x - k * L;
            if (w >= L / 2) w -= L; // rounding at the edge
            position.push_back(float(w));
            image.push_back(static_cast<std::int32_t>(k));
            velocity.push_back(float(s.velocity[i][c] * perPs));
        }
        Quat q = Quat::Identity();
        if (!s.orientation.empty())
            q = s.orientation[i];
        else if (type.inertia.squaredNorm() > 0)
            q = Quat::FromTwoVectors(Vec3::UnitZ(), s.axis[i]);
        q.normalize();
        orientation.insert(orientation.end(),
                           {float(q.w()), float(q.x()), float(q.y()), float(q.z())});
        // L_body = I ω_body; HOOMD keeps p = 2 q ⊗ (0, L_body) (Kamberaj, Low and Neal, J. Chem.
        // Phys. 122, 224114 (2005)), from which L_body = ½ (q* ⊗ p).vec.
        Vec3 omegaBody = s.omega.empty() ? Vec3::Zero() : Vec3(q.conjugate() * s.omega[i] * perPs);
        const Vec3 lBody = type.inertia.cwiseProduct(omegaBody);
        const Quat p = q * Quat(0.0, lBody.x(), lBody.y(), lBody.z());
        angmom.insert(angmom.end(),
                      {float(2 * p.w()), float(2 * p.x()), float(2 * p.y()), float(2 * p.z())});
    }
    chunk(f, "particles/position", GsdType::Float, n, 3, position);
    chunk(f, "particles/image", GsdType::Int32, n, 3, image);
    chunk(f, "particles/orientation", GsdType::Float, n, 4, orientation);
    chunk(f, "particles/velocity", GsdType::Float, n, 3, velocity);
    chunk(f, "particles/angmom", GsdType::Float, n, 4, angmom);
    chunk(f, "log/time_ps", GsdType::Double, 1, 1, std::vector<double>{units::toPs(s.time)});
    f.endFrame();
}

} // namespace terrace
