#include "core/gsd_frame.hpp"
#include "core/units.hpp"
#include "core/xyz.hpp"
#include <cmath>
#include <cstring>
#include <map>

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
    for (const auto& x : scene.species) {
        t.species.push_back(x.name);
        const double sigma = x.sigma * scene.potential.sigma;
        t.speciesShapes.push_back(nlohmann::json{{"type", "Sphere"}, {"diameter", sigma}});
        t.speciesMasses.push_back(x.mass * scene.body.mass);
        if (x.kind.empty()) continue; // a mixture of spheres
        // Rods among spheres (core/species_rotor.hpp): a rod species is drawn as the rods are.
        const double I = x.kind == "sphere" ? 0.0 : x.inertia * scene.body.inertia[0];
        t.speciesInertia.push_back(Vec3(I, I, 0.0));
        if (x.kind != "sphere")
            t.speciesShapes.back() = {
                {"type", "ConvexPolyhedron"},
                {"rounding_radius", sigma / 2},
                {"vertices",
                 {{0.0, 0.0, -scene.potential.zeta / 2}, {0.0, 0.0, scene.potential.zeta / 2}}}};
    }
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

void writeConstantChunks(GsdWriter& f, std::uint32_t n, double boxLength, const GsdBodyType& type) {
    const float L = float(boxLength);
    chunk(f, "configuration/box", GsdType::Float, 6, 1, std::vector<float>{L, L, L, 0, 0, 0});
    chunk(f, "particles/N", GsdType::UInt32, 1, 1, std::vector<std::uint32_t>{n});
    std::uint32_t width = 0;
    const std::vector<std::string> typeNames =
        type.species.empty() ? std::vector<std::string>{type.name} : type.species;
    const auto names = stringRows(typeNames, width);
    chunk(f, "particles/types", GsdType::Int8, typeNames.size(), width, names);
    // A mixture's typeid and mass follow its bodies' species, written with the first frame's
    // bodies.
    if (type.species.empty()) {
        chunk(f, "particles/typeid", GsdType::UInt32, n, 1, std::vector<std::uint32_t>(n, 0));
        chunk(f, "particles/mass", GsdType::Float, n, 1, std::vector<float>(n, float(type.mass)));
    }
    if (type.speciesInertia.empty()) {
        std::vector<float> inertia;
        inertia.reserve(3 * std::size_t(n));
        for (std::uint32_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c)
                inertia.push_back(float(type.inertia[c]));
        chunk(f, "particles/moment_inertia", GsdType::Float, n, 3, inertia);
    }
    std::vector<std::string> shapeRows{type.shape.dump()};
    if (!type.species.empty()) {
        shapeRows.clear();
        for (const auto& shape : type.speciesShapes)
            shapeRows.push_back(shape.dump());
    }
    const auto shapes = stringRows(shapeRows, width);
    chunk(f, "particles/type_shapes", GsdType::Int8, shapeRows.size(), width, shapes);
}

/// Body i's orientation as HOOMD reads it (s x y z): a top's own; a linear rotor's rotation of
/// least angle taking the body z axis to its axis; a sphere's identity.
Quat orientationOf(const Snapshot& s, int i, const GsdBodyType& type) {
    Quat q = Quat::Identity();
    if (!s.orientation.empty())
        q = s.orientation[i];
    else if (type.inertia.squaredNorm() > 0)
        q = Quat::FromTwoVectors(Vec3::UnitZ(), s.axis[i]);
    return q.normalized();
}

/// One per-body chunk, computed piece by piece: `each(snapshot, i, out)` appends body i's m values.
template <class T>
void bodyChunk(GsdWriter& f, const char* name, GsdType type, std::uint32_t m, int bodies,
               const std::function<Snapshot(int, int)>& bodiesOf, int perPiece,
               const std::function<void(const Snapshot&, int, std::vector<T>&)>& each) {
    f.writeChunkPieces(name, type, std::uint64_t(bodies), m, [&](const PieceSink& sink) {
        std::vector<T> out;
        for (int begin = 0; begin < bodies; begin += perPiece) {
            const int end = std::min(bodies, begin + perPiece);
            const Snapshot piece = bodiesOf(begin, end);
            if (piece.size() != end - begin)
                throw std::logic_error("writeHoomdFrame: a piece of the wrong size");
            out.clear();
            for (int i = 0; i < piece.size(); ++i)
                each(piece, i, out);
            sink(std::string_view(reinterpret_cast<const char*>(out.data()),
                                  out.size() * sizeof(T)));
        }
    });
}

} // namespace

void writeHoomdFrame(GsdWriter& f, int bodies, double time, double boxLength,
                     const std::function<Snapshot(int, int)>& bodiesOf, const GsdBodyType& type,
                     std::uint64_t sample, int perPiece) {
    if (perPiece < 1) throw std::invalid_argument("writeHoomdFrame: no bodies per piece");
    if (f.frames() == 0) {
        writeConstantChunks(f, std::uint32_t(bodies), boxLength, type);
        if (!type.species.empty()) {
            bodyChunk<std::uint32_t>(
                f, "particles/typeid", GsdType::UInt32, 1, bodies, bodiesOf, perPiece,
                [](const Snapshot& s, int i, std::vector<std::uint32_t>& out) {
                    if (s.species.empty())
                        throw std::logic_error(
                            "writeHoomdFrame: a mixture's bodies without species");
                    out.push_back(static_cast<std::uint32_t>(s.species[i]));
                });
            bodyChunk<float>(f, "particles/mass", GsdType::Float, 1, bodies, bodiesOf, perPiece,
                             [&](const Snapshot& s, int i, std::vector<float>& out) {
                                 out.push_back(float(type.speciesMasses.at(s.species[i])));
                             });
        }
        if (!type.speciesInertia.empty())
            bodyChunk<float>(f, "particles/moment_inertia", GsdType::Float, 3, bodies, bodiesOf,
                             perPiece, [&](const Snapshot& s, int i, std::vector<float>& out) {
                                 const Vec3& I = type.speciesInertia.at(s.species[i]);
                                 for (int c = 0; c < 3; ++c)
                                     out.push_back(float(I[c]));
                             });
    }
    chunk(f, "configuration/step", GsdType::UInt64, 1, 1, std::vector<std::uint64_t>{sample});
    const double L = boxLength, perPs = 1.0 / units::psPerTimeUnit;
    // HOOMD's box spans [-L/2, L/2): our unwrapped positions are taken into it, and the images
    // counted, so that unwrapped = position + image·L.
    const auto image = [L](double x) { return std::floor(x / L + 0.5); };
    bodyChunk<float>(f, "particles/position", GsdType::Float, 3, bodies, bodiesOf, perPiece,
                     [&](const Snapshot& s, int i, std::vector<float>& out) {
                         for (int c = 0; c < 3; ++c) {
                             const double x = s.position[i][c];
                             double w = x - image(x) * L;
                             if (w >= L / 2) w -= L; // rounding at the edge
                             out.push_back(float(w));
                         }
                     });
    bodyChunk<std::int32_t>(f, "particles/image", GsdType::Int32, 3, bodies, bodiesOf, perPiece,
                            [&](const Snapshot& s, int i, std::vector<std::int32_t>& out) {
                                for (int c = 0; c < 3; ++c) {
                                    const double x = s.position[i][c];
                                    double k = image(x);
                                    if (x - k * L >= L / 2) k += 1; // as the position's edge
                                    out.push_back(static_cast<std::int32_t>(k));
                                }
                            });
    bodyChunk<float>(
        f, "particles/orientation", GsdType::Float, 4, bodies, bodiesOf, perPiece,
        [&](const Snapshot& s, int i, std::vector<float>& out) {
            const Quat q = orientationOf(s, i, type);
            out.insert(out.end(), {float(q.w()), float(q.x()), float(q.y()), float(q.z())});
        });
    bodyChunk<float>(f, "particles/velocity", GsdType::Float, 3, bodies, bodiesOf, perPiece,
                     [&](const Snapshot& s, int i, std::vector<float>& out) {
                         for (int c = 0; c < 3; ++c)
                             out.push_back(float(s.velocity[i][c] * perPs));
                     });
    bodyChunk<float>(f, "particles/angmom", GsdType::Float, 4, bodies, bodiesOf, perPiece,
                     [&](const Snapshot& s, int i, std::vector<float>& out) {
                         // L_body = I ω_body; HOOMD keeps p = 2 q ⊗ (0, L_body) (Kamberaj, Low and
                         // Neal, J. Chem. Phys. 122, 224114 (2005)), from which L_body = ½ (q* ⊗
                         // p).vec.
                         const Quat q = orientationOf(s, i, type);
                         const Vec3 omegaBody = s.omega.empty()
                                                    ? Vec3::Zero()
                                                    : Vec3(q.conjugate() * (s.omega[i] * perPs));
                         const Vec3& I = type.speciesInertia.empty()
                                             ? type.inertia
                                             : type.speciesInertia.at(s.species[i]);
                         const Vec3 l = I.cwiseProduct(omegaBody);
                         const Quat p = q * Quat(0.0, l.x(), l.y(), l.z());
                         out.insert(out.end(), {float(2 * p.w()), float(2 * p.x()),
                                                float(2 * p.y()), float(2 * p.z())});
                     });
    chunk(f, "log/time_ps", GsdType::Double, 1, 1, std::vector<double>{units::toPs(time)});
    f.endFrame();
}

void writeHoomdFrame(GsdWriter& f, const Snapshot& s, const GsdBodyType& type,
                     std::uint64_t sample) {
    const auto bodiesOf = [&s](int begin, int end) {
        Snapshot piece;
        piece.time = s.time;
        piece.boxLength = s.boxLength;
        const auto take = [&](const auto& from, auto& to) {
            if (!from.empty()) to.assign(from.begin() + begin, from.begin() + end);
        };
        take(s.position, piece.position);
        take(s.velocity, piece.velocity);
        take(s.axis, piece.axis);
        take(s.omega, piece.omega);
        take(s.orientation, piece.orientation);
        take(s.species, piece.species);
        return piece;
    };
    writeHoomdFrame(f, s.size(), s.time, s.boxLength, bodiesOf, type, sample);
}

namespace {

template <class T>
std::vector<T> chunkValues(const std::filesystem::path& path, const GsdIndexEntry& e,
                           std::uint32_t m, std::uint64_t n) {
    if (e.m != m || e.n != n || gsdTypeSize(e.type) != sizeof(T))
        throw TrajectoryError(path.string() + ": chunk of frame " + std::to_string(e.frame) +
                              " is not the shape this program writes");
    const std::string raw = readGsdChunk(path, e);
    std::vector<T> v(raw.size() / sizeof(T));
    std::memcpy(v.data(), raw.data(), raw.size());
    return v;
}

} // namespace

long forEachGsdFrame(const std::filesystem::path& path,
                     const std::function<void(Snapshot&&)>& each) {
    const GsdContents c = readGsdContents(path);
    if (c.schema != "hoomd") throw TrajectoryError(path.string() + ": not a HOOMD-schema GSD file");
    // Per frame, its chunks by name (the index is in frame order).
    std::vector<std::map<std::string, const GsdIndexEntry*>> frames;
    for (const auto& e : c.index) {
        if (e.frame >= frames.size()) frames.resize(e.frame + 1);
        frames[e.frame][c.names[e.id]] = &e;
    }
    if (frames.empty()) return 0;
    const auto need = [&](std::size_t f, const std::string& name) -> const GsdIndexEntry& {
        const auto it = frames[f].find(name);
        if (it == frames[f].end())
            throw TrajectoryError(path.string() + ": frame " + std::to_string(f) + " has no " +
                                  name);
        return *it->second;
    };
    const auto n = chunkValues<std::uint32_t>(path, need(0, "particles/N"), 1, 1).at(0);
    const float L = chunkValues<float>(path, need(0, "configuration/box"), 1, 6).at(0);
    const auto inertia = chunkValues<float>(path, need(0, "particles/moment_inertia"), 3, n);
    const Vec3 moments = n ? Vec3(inertia[0], inertia[1], inertia[2]) : Vec3::Zero();
    const bool top = moments.minCoeff() > 0;
    const double perTimeUnit = units::psPerTimeUnit; // per ps -> per time unit
    long handed = 0;
    for (std::size_t f = 0; f < frames.size(); ++f) {
        const auto time = chunkValues<double>(path, need(f, "log/time_ps"), 1, 1).at(0);
        const auto pos = chunkValues<float>(path, need(f, "particles/position"), 3, n);
        const auto img = chunkValues<std::int32_t>(path, need(f, "particles/image"), 3, n);
        const auto vel = chunkValues<float>(path, need(f, "particles/velocity"), 3, n);
        const auto ori = chunkValues<float>(path, need(f, "particles/orientation"), 4, n);
        const auto mom = chunkValues<float>(path, need(f, "particles/angmom"), 4, n);
        Snapshot s;
        s.time = units::fromPs(time);
        s.boxLength = L;
        for (std::uint32_t i = 0; i < n; ++i) {
            s.position.emplace_back(pos[3 * i] + double(img[3 * i]) * L,
                                    pos[3 * i + 1] + double(img[3 * i + 1]) * L,
                                    pos[3 * i + 2] + double(img[3 * i + 2]) * L);
            s.velocity.emplace_back(vel[3 * i] * perTimeUnit, vel[3 * i + 1] * perTimeUnit,
                                    vel[3 * i + 2] * perTimeUnit);
            const Quat q =
                Quat(ori[4 * i], ori[4 * i + 1], ori[4 * i + 2], ori[4 * i + 3]).normalized();
            s.axis.push_back(q * Vec3::UnitZ());
            if (top) s.orientation.push_back(q);
            // ω_body = L_body / I about the axes with a moment; L_body = ½ (q* ⊗ p).vec.
            const Quat p(mom[4 * i], mom[4 * i + 1], mom[4 * i + 2], mom[4 * i + 3]);
            const Quat lb = q.conjugate() * p;
            Vec3 omegaBody = Vec3::Zero();
            // Each body's own moments: among rods a sphere's are 0 (no ω), a rod's its species'.
            const Vec3 own(inertia[3 * i], inertia[3 * i + 1], inertia[3 * i + 2]);
            for (int k = 0; k < 3; ++k)
                if (own[k] > 0) omegaBody[k] = 0.5 * lb.vec()[k] / own[k];
            s.omega.push_back(q * omegaBody * perTimeUnit);
        }
        each(std::move(s));
        ++handed;
    }
    return handed;
}

} // namespace terrace
