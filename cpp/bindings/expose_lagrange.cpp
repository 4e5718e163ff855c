// Bindings of paper 003's models (heavy symmetric top, full and averaged over nutation): type
// translation only; the physics is in model/lagrange_top.hpp, model/lagrange_averaged.hpp.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "expose.hpp"
#include "gyrostat/model/lagrange_top.hpp"

namespace gyrostat::bindings {


void expose_lagrange(py::module_& m) {
    py::class_<model::Nutation>(m, "LagrangeNutation")
        .def_readonly("u1", &model::Nutation::u1)
        .def_readonly("u2", &model::Nutation::u2)
        .def_readonly("u3", &model::Nutation::u3)
        .def_readonly("m", &model::Nutation::m)
        .def_readonly("alpha", &model::Nutation::alpha)
        .def_readonly("v", &model::Nutation::v)
        .def_readonly("period", &model::Nutation::period);

    m.def("lagrange_nutation", &model::nutation, py::arg("A"), py::arg("C"), py::arg("mu"), py::arg("G_z"), py::arg("H"),
          py::arg("r"));
    m.def(
        "lagrange_nutation_slopes",
        [](double A, double C, double mu, double Gz, double H, double r) {
            const model::NutationSlopes s = model::nutation_slopes(A, C, mu, Gz, H, r, model::nutation(A, C, mu, Gz, H, r));
            return std::make_tuple(s.Gz, s.H, s.r, s.mu);
        },
        py::arg("A"), py::arg("C"), py::arg("mu"), py::arg("G_z"), py::arg("H"), py::arg("r"),
        "(dv/dG_z, dv/dH, dv/dr, dv/dmu) of v = <cos theta> over the nutation, at fixed A and C");
    m.def(
        "lagrange_nutation_table",
        [](double A, double C, double mu, const std::vector<double>& Gz, const std::vector<double>& H,
           const std::vector<double>& r) {
            if (Gz.size() != H.size() || Gz.size() != r.size())
                throw std::invalid_argument("lagrange_nutation_table: G_z, H, r must have one length; got " +
                                            std::to_string(Gz.size()) + ", " + std::to_string(H.size()) + ", " +
                                            std::to_string(r.size()));
            py::array_t<double> out({static_cast<py::ssize_t>(Gz.size()), py::ssize_t(7)});
            double* data = out.mutable_data();
            {
                py::gil_scoped_release release;
                for (std::size_t i = 0; i < Gz.size(); ++i) {
                    const model::Nutation n = model::nutation(A, C, mu, Gz[i], H[i], r[i]);
                    const double row[7] = {n.u1, n.u2, n.u3, n.m, n.alpha, n.v, n.period};
                    std::copy(row, row + 7, data + 7 * i);
                }
            }
            return out;
        },
        py::arg("A"), py::arg("C"), py::arg("mu"), py::arg("G_z"), py::arg("H"), py::arg("r"),
        "Rows (u1, u2, u3, m, alpha, v, period) for each (G_z, H, r).");
    m.def("elliptic_K", &model::elliptic_K, py::arg("m"), "K(m), parameter m = k^2 (GSL)");
    m.def("elliptic_E", &model::elliptic_E, py::arg("m"), "E(m), parameter m = k^2 (GSL)");
    m.def("jacobi_sn_cn_dn", &model::jacobi_sn_cn_dn, py::arg("u"), py::arg("m"), "(sn, cn, dn)(u | m) (GSL)");
    m.def(
        "complete_elliptic",
        [](double k2, double k2_complement) {
            const model::CompleteIntegrals c = model::complete_integrals_checked(k2, k2_complement);
            return std::make_pair(c.K, c.mean_sn_squared);
        },
        py::arg("m"), py::arg("m1"),
        "(K(m), <sn^2> = (K - E)/(m K)) by polynomial pieces (the triaxial averaged model's), m read up to 1/2 "
        "and its complement m1 = 1 - m beyond");
    m.def("mean_sn_squared", &model::mean_sn_squared, py::arg("m"), "W(m) = (K - E)/(m K) = <sn^2>");

    py::class_<model::LagrangeUnperturbed>(m, "LagrangeUnperturbed")
        .def(py::init<double, double, double, const Vec3&, const Vec3&, double>(), py::arg("A"), py::arg("C"),
             py::arg("mu"), py::arg("omega"), py::arg("gamma"), py::arg("t0") = 0.0)
        .def("u",
             [](const model::LagrangeUnperturbed& s, const std::vector<double>& t) {
                 std::vector<double> out(t.size());
                 {
                     py::gil_scoped_release release;
                     for (std::size_t i = 0; i < t.size(); ++i) out[i] = s.u(t[i]);
                 }
                 return out;
             },
             py::arg("t"))
        .def_property_readonly("nutation", &model::LagrangeUnperturbed::nutation)
        .def_property_readonly("G_z", &model::LagrangeUnperturbed::Gz)
        .def_property_readonly("H", &model::LagrangeUnperturbed::H)
        .def_property_readonly("r", &model::LagrangeUnperturbed::r)
        .def_property_readonly("beta", &model::LagrangeUnperturbed::beta);
}

}  // namespace gyrostat::bindings
