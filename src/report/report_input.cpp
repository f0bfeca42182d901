#include "report/report_input.hpp"

namespace revisit {

PrCurvePoint MaxF1(const PrCurve& curve) {
    if (curve.max_f1) return *curve.max_f1;
    PrCurvePoint best;
    for (const auto& p : curve.points)
        if (p.F1() > best.F1()) best = p;
    return best;
}

}  // namespace revisit
