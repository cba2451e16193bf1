# All dependencies are Debian 12 packages (installed by scripts/setup.sh).
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(TBB REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(assimp REQUIRED)
find_package(tinyobjloader REQUIRED)
find_package(TinyGLTF REQUIRED)
find_package(embree 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(Threads REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)
# FFTW3 (DCT Poisson solve of the density-flow warp, src/adapt/density_flow/density_flow.cpp).
pkg_check_modules(FFTW3 REQUIRED IMPORTED_TARGET fftw3)

