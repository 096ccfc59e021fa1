#include "experiments/tools/potential_map.hpp"
#include "core/rod_potential.hpp"
#include "dmd/terrace_levels.hpp"
#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace terrace::experiments {

void writePotentialMap(const std::filesystem::path& csv, const PotentialMapSettings& s) {
    const RodPotential potential{s.epsilon, s.sigma, s.zeta};
    const auto levels = dmd::TerraceLevels::uniform(s.dV);
    std::ofstream out(csv);
    if (!out) throw std::runtime_error(csv.string() + ": cannot write");
    out.precision(7); // a figure's data: seven digits are plenty and keep the file small
    out << "r,c,U,V\n";
    for (int i = 0; i < s.rPoints; ++i) {
        const double r = s.rMin + (s.rMax - s.rMin) * i / (s.rPoints - 1);
        for (int k = 0; k < s.cPoints; ++k) {
            const double c = -1.0 + 2.0 * k / (s.cPoints - 1);
            // Two unit axes with s_i·s_j = c, the separation along x (U depends on r and c only).
            const Vec3 si(0, 0, 1), sj(0, std::sqrt(std::max(0.0, 1.0 - c * c)), c);
            const double U = potential.energy(Vec3(r, 0, 0), si, sj);
            const double V = std::max(s.vMin, levels.energy(levels.terraceOf(U)));
            out << r << ',' << c << ',' << U << ',' << V << '\n';
        }
        out << '\n';
    }
}

} // namespace terrace::experiments
