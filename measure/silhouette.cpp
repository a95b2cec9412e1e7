#include "measure/silhouette.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "measure/image_diff.h"

namespace rtm {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// 1-D squared distance transform of f (n samples, stride apart) in place: d(q) = min_p (q - p)^2 + f(p).
void transform_1d(double* f, int n, int stride, std::vector<double>& d, std::vector<int>& v, std::vector<double>& z) {
    d.resize(size_t(n));
    v.resize(size_t(n));
    z.resize(size_t(n) + 1);
    int k = -1;
    for (int q = 0; q < n; ++q) {
        const double fq = f[size_t(q) * size_t(stride)];
        if (fq == kInf) continue;
        double s = -kInf;
        while (k >= 0) {
            const int p = v[size_t(k)];
            const double fp = f[size_t(p) * size_t(stride)];
            s = ((fq + double(q) * q) - (fp + double(p) * p)) / (2.0 * (q - p));
            if (s > z[size_t(k)]) break;
            --k;
        }
        ++k;
        v[size_t(k)] = q;
        z[size_t(k)] = k == 0 ? -kInf : s;
        z[size_t(k) + 1] = kInf;
    }
    if (k < 0) return;  // all infinite: stays infinite
    int j = 0;
    for (int q = 0; q < n; ++q) {
        while (z[size_t(j) + 1] < q) ++j;
        const int p = v[size_t(j)];
        d[size_t(q)] = double(q - p) * (q - p) + f[size_t(p) * size_t(stride)];
    }
    for (int q = 0; q < n; ++q) f[size_t(q) * size_t(stride)] = d[size_t(q)];
}

}  // namespace

std::vector<unsigned char> silhouette_mask(const ImageRGBA8& img) {
    const int w = img.width, h = img.height;
    std::vector<unsigned char> m(size_t(w) * size_t(h), 0);
    const auto cov = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && covered(img.at(x, y)); };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (cov(x, y) && !(cov(x - 1, y) && cov(x + 1, y) && cov(x, y - 1) && cov(x, y + 1)))
                m[size_t(y) * size_t(w) + size_t(x)] = 1;
    return m;
}

std::vector<double> squared_distance_transform(const std::vector<unsigned char>& mask, int w, int h) {
    std::vector<double> f(size_t(w) * size_t(h));
    for (size_t i = 0; i < f.size(); ++i) f[i] = mask[i] ? 0.0 : kInf;
    std::vector<double> d, z;
    std::vector<int> v;
    for (int x = 0; x < w; ++x) transform_1d(f.data() + x, h, w, d, v, z);                      // columns
    for (int y = 0; y < h; ++y) transform_1d(f.data() + size_t(y) * size_t(w), w, 1, d, v, z);  // rows
    return f;
}

std::vector<double> squared_distance_transform_naive(const std::vector<unsigned char>& mask, int w, int h) {
    std::vector<double> f(size_t(w) * size_t(h), kInf);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int py = 0; py < h; ++py)
                for (int px = 0; px < w; ++px)
                    if (mask[size_t(py) * size_t(w) + size_t(px)]) {
                        const double dd = double(x - px) * (x - px) + double(y - py) * (y - py);
                        double& o = f[size_t(y) * size_t(w) + size_t(x)];
                        if (dd < o) o = dd;
                    }
    return f;
}

double silhouette_error(const ImageRGBA8& ref, const ImageRGBA8& test) {
    if (ref.width != test.width || ref.height != test.height)
        throw std::invalid_argument("silhouette_error: reference is " + std::to_string(ref.width) + "x" +
                                    std::to_string(ref.height) + " but test is " + std::to_string(test.width) + "x" +
                                    std::to_string(test.height));
    const std::vector<unsigned char> r = silhouette_mask(ref), t = silhouette_mask(test);
    long long n_ref = 0, n_test = 0;
    for (size_t i = 0; i < r.size(); ++i) {
        n_ref += r[i];
        n_test += t[i];
    }
    if (n_ref == 0 && n_test == 0) return 0.0;
    if (n_ref == 0 || n_test == 0) return std::nan("");
    const std::vector<double> d2 = squared_distance_transform(r, ref.width, ref.height);
    double sum = 0.0;
    for (size_t i = 0; i < t.size(); ++i)
        if (t[i]) sum += std::sqrt(d2[i]);
    return sum / double(n_test);
}

}  // namespace rtm
