// PluginLoader against real fixture libraries (tests/plugin/fixtures),
// each case built into its own folder under SERVOLOOP_TEST_PLUGIN_DIR.
#include <dlfcn.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fixture_bases.hpp"
#include "servoloop/plugin/plugin_loader.hpp"
#include "servoloop/core/errors.hpp"

#include "temp_dir.hpp"

namespace servoloop::plugin {
namespace {

namespace fs = std::filesystem;
using test_fixtures::FixtureController;
using test_fixtures::FixtureCounters;
using test_fixtures::FixtureRobot;
using ::testing::HasSubstr;

fs::path caseDir(const std::string& name) { return fs::path(SERVOLOOP_TEST_PLUGIN_DIR) / name; }
fs::path caseLibrary(const std::string& name) {
  return caseDir(name) / ("libfixture_" + name + ".so");
}

// The one diagnostic about `library`; fails the test if there is not exactly one.
PluginDiagnostic diagnosticFor(const PluginLoader& loader, const fs::path& library) {
  std::vector<PluginDiagnostic> found;
  for (const auto& diagnostic : loader.diagnostics()) {
    if (diagnostic.library == library) found.push_back(diagnostic);
  }
  EXPECT_EQ(found.size(), 1u) << "diagnostics about " << library;
  return found.empty() ? PluginDiagnostic{} : found.front();
}

std::string errorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const servoloop::Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected servoloop::Error";
  return "";
}

// Asks the dynamic linker whether `library` is still mapped, without loading it.
bool isLoaded(const fs::path& library) {
  void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_NOLOAD);
  if (handle == nullptr) return false;
  dlclose(handle);
  return true;
}

FixtureCounters& goodLibraryCounters() {
  void* handle = dlopen(caseLibrary("good").c_str(), RTLD_NOW | RTLD_NOLOAD);
  EXPECT_NE(handle, nullptr) << "libfixture_good.so is not loaded";
  auto counters = reinterpret_cast<FixtureCountersFn>(dlsym(handle, "servoloop_fixture_good_counters"));
  EXPECT_NE(counters, nullptr);
  dlclose(handle);  // the loader's own reference keeps it mapped
  return *counters();
}

TEST(PluginLoader, ListsEveryTypeOfAGoodLibraryRegisteredFromSeveralSources) {
  PluginLoader loader({caseDir("good")});
  EXPECT_TRUE(loader.diagnostics().empty());

  const auto all = loader.listTypes();
  ASSERT_EQ(all.size(), 4u);
  // Sorted by type name, each with its kind and the library's absolute path.
  EXPECT_EQ(all[0].type, "fixture/Alpha");
  EXPECT_EQ(all[1].type, "fixture/Beta");
  EXPECT_EQ(all[2].type, "fixture/Robot");
  EXPECT_EQ(all[3].type, "fixture/ThrowingController");
  EXPECT_EQ(all[2].kind, "robot_hw");
  for (const auto& type : all) EXPECT_EQ(type.library, fs::canonical(caseLibrary("good")));

  const auto controllers = loader.listTypes("controller");
  ASSERT_EQ(controllers.size(), 3u);
  for (const auto& type : controllers) EXPECT_EQ(type.kind, "controller");
  EXPECT_TRUE(loader.hasType("fixture/Robot"));
  EXPECT_FALSE(loader.hasType("fixture/Nothing"));
  // Listing read the plugin index from the file: the library was never loaded.
  EXPECT_FALSE(isLoaded(caseLibrary("good")));
}

TEST(PluginLoader, ListingRunsNoPluginCode) {
  // This library's static constructor aborts the process: listing it, asking
  // for its type and reloading must never load it.
  PluginLoader loader({caseDir("aborting_constructor")});
  EXPECT_TRUE(loader.diagnostics().empty());
  const auto types = loader.listTypes();
  ASSERT_EQ(types.size(), 1u);
  EXPECT_EQ(types[0].type, "fixture/AbortsWhenLoaded");
  EXPECT_EQ(types[0].kind, "controller");
  EXPECT_TRUE(loader.hasType("fixture/AbortsWhenLoaded"));
  loader.reload();
  EXPECT_EQ(loader.listTypes().size(), 1u);
  EXPECT_FALSE(isLoaded(caseLibrary("aborting_constructor")));
}

TEST(PluginLoader, ALibraryIsLoadedWhenOneOfItsTypesIsFirstCreated) {
  PluginLoader loader({caseDir("good")});
  EXPECT_FALSE(isLoaded(caseLibrary("good")));
  auto beta = loader.create<FixtureController>("fixture/Beta");
  EXPECT_TRUE(isLoaded(caseLibrary("good")));
  // The library's other types are bound by the same load.
  EXPECT_EQ(loader.create<FixtureRobot>("fixture/Robot")->jointCount(), 3);
}

TEST(PluginLoader, CreatesObjectsOfEachKindThroughTheLibraryFactory) {
  PluginLoader loader({caseDir("good")});
  auto alpha = loader.create<FixtureController>("fixture/Alpha");
  auto beta = loader.create<FixtureController>("fixture/Beta");
  auto robot = loader.create<FixtureRobot>("fixture/Robot");
  ASSERT_TRUE(alpha && beta && robot);
  EXPECT_EQ(alpha->name(), "alpha");
  EXPECT_EQ(beta->name(), "beta");
  EXPECT_EQ(robot->jointCount(), 3);
  EXPECT_EQ(loader.liveObjectCount(), 3u);
  beta.reset();
  EXPECT_EQ(loader.liveObjectCount(), 2u);
}

TEST(PluginLoader, ObjectsAreDestroyedAndFreedByTheLibrarysDeleter) {
  PluginLoader loader({caseDir("good")});
  auto beta = loader.create<FixtureController>("fixture/Beta");  // loads the library
  FixtureCounters& counters = goodLibraryCounters();
  const FixtureCounters before = counters;

  auto alpha = loader.create<FixtureController>("fixture/Alpha");
  EXPECT_EQ(counters.alpha_constructed, before.alpha_constructed + 1);
  // Converting to shared_ptr keeps the library's deleter.
  std::shared_ptr<FixtureController> shared = std::move(alpha);
  shared.reset();

  EXPECT_EQ(counters.alpha_destroyed, before.alpha_destroyed + 1);
  EXPECT_EQ(counters.alpha_freed_by_library_delete, before.alpha_freed_by_library_delete + 1);
  beta.reset();
  EXPECT_EQ(loader.liveObjectCount(), 0u);
}

TEST(PluginLoader, LibraryStaysLoadedWhileItsObjectsExistAndUnloadsAfter) {
  const fs::path library = caseLibrary("good");
  ASSERT_FALSE(isLoaded(library)) << "another test leaked the fixture library";
  {
    PluginPtr<FixtureController> alpha;
    {
      PluginLoader loader({caseDir("good")});
      alpha = loader.create<FixtureController>("fixture/Alpha");
    }
    // The loader is gone; the object still runs code of the library.
    EXPECT_TRUE(isLoaded(library));
    EXPECT_EQ(alpha->name(), "alpha");
  }
  EXPECT_FALSE(isLoaded(library));
}

TEST(PluginLoader, ConstructorExceptionNamesTypeAndLibrary) {
  PluginLoader loader({caseDir("good")});
  const std::string message =
      errorOf([&] { loader.create<FixtureController>("fixture/ThrowingController"); });
  EXPECT_THAT(message, HasSubstr("'fixture/ThrowingController'"));
  EXPECT_THAT(message, HasSubstr(caseLibrary("good").filename().string()));
  EXPECT_THAT(message, HasSubstr("fixture constructor fails on purpose"));
  EXPECT_EQ(loader.liveObjectCount(), 0u);
}

TEST(PluginLoader, UnknownTypeListsTheKnownTypesOfThatKind) {
  PluginLoader loader({caseDir("good")});
  const std::string message = errorOf([&] { loader.create<FixtureController>("fixture/Gamma"); });
  EXPECT_THAT(message, HasSubstr("unknown controller type 'fixture/Gamma'"));
  EXPECT_THAT(message, HasSubstr("fixture/Alpha, fixture/Beta, fixture/ThrowingController"));
  EXPECT_THAT(message, ::testing::Not(HasSubstr("fixture/Robot")));
}

TEST(PluginLoader, UnknownTypeWithNoPluginsSaysWhereItLooked) {
  const servoloop::testing::TempDir temp("servoloop-plugin-loader");
  const fs::path empty = temp.path() / "empty";
  fs::create_directories(empty);
  const fs::path missing = temp.path() / "no_such_dir";
  PluginLoader loader({empty, missing});
  EXPECT_TRUE(loader.listTypes().empty());
  const std::string message = errorOf([&] { loader.create<FixtureController>("fixture/Alpha"); });
  EXPECT_THAT(message, HasSubstr("no controller plugins found in"));
  EXPECT_THAT(message, HasSubstr(empty.string()));
  EXPECT_THAT(message, HasSubstr(missing.string() + " (missing)"));
  EXPECT_THAT(message, HasSubstr("SERVOLOOP_PLUGIN_PATH"));
}

// Declares the same kind as FixtureController but is an unrelated class.
struct OtherControllerBase {
  static constexpr const char* kPluginKind = "controller";
  virtual ~OtherControllerBase() = default;
};

TEST(PluginLoader, CreatingAsTheWrongKindOrBaseIsRefused) {
  PluginLoader loader({caseDir("good")});
  EXPECT_THAT(errorOf([&] { loader.create<FixtureController>("fixture/Robot"); }),
              HasSubstr("'fixture/Robot'"));
  EXPECT_THAT(errorOf([&] { loader.create<FixtureController>("fixture/Robot"); }),
              HasSubstr("is a robot_hw plugin, not a controller plugin"));

  // Same kind string, unrelated base class.
  const std::string message = errorOf([&] { loader.create<OtherControllerBase>("fixture/Alpha"); });
  EXPECT_THAT(message, HasSubstr("derives from servoloop::test_fixtures::FixtureController"));
}

// A library or folder every user can write to could bring another user's
// code into this process: it is not loaded, with one diagnostic saying why.
TEST(PluginLoader, WorldWritableLibrariesAndFoldersAreNotLoaded) {
  servoloop::testing::TempDir dir("servoloop-plugin-perm");
  const fs::path library = dir.path() / "libfixture_good.so";
  fs::copy_file(caseLibrary("good"), library);
  fs::permissions(library, fs::perms::others_write, fs::perm_options::add);
  {
    PluginLoader loader({dir.path()});
    EXPECT_FALSE(loader.hasType("fixture/Alpha"));
    const PluginDiagnostic diagnostic = diagnosticFor(loader, fs::canonical(library));
    EXPECT_THAT(diagnostic.reason, HasSubstr("not loaded: it is writable by every user (mode 0"));
    EXPECT_THAT(diagnostic.reason, HasSubstr("chmod o-w"));
  }
  fs::permissions(library, fs::perms::others_write, fs::perm_options::remove);
  EXPECT_TRUE(PluginLoader({dir.path()}).hasType("fixture/Alpha"));

  fs::permissions(dir.path(), fs::perms::others_write, fs::perm_options::add);
  PluginLoader loader({dir.path()});
  EXPECT_FALSE(loader.hasType("fixture/Alpha"));
  const PluginDiagnostic diagnostic = diagnosticFor(loader, dir.path());
  EXPECT_THAT(diagnostic.reason, HasSubstr("plugin folder not searched: it is writable by every user"));
  fs::permissions(dir.path(), fs::perms::others_write, fs::perm_options::remove);
}

TEST(PluginLoader, LibraryWithoutAPluginIndexIsPassedOverQuietly) {
  // A valid shared library that is not a servoloop plugin: no warning, no type.
  PluginLoader loader({caseDir("not_a_plugin")});
  EXPECT_TRUE(loader.diagnostics().empty());
  EXPECT_TRUE(loader.listTypes().empty());
  EXPECT_FALSE(isLoaded(caseLibrary("not_a_plugin")));
}

TEST(PluginLoader, WrongApiVersionInTheIndexIsRefusedWithoutLoading) {
  // The fixture's entries point at address 0x10: reading them would crash.
  PluginLoader loader({caseDir("wrong_api_version")});
  const auto diagnostic = diagnosticFor(loader, fs::canonical(caseLibrary("wrong_api_version")));
  EXPECT_THAT(diagnostic.reason, HasSubstr("wrong plugin API version: built for version 1"));
  EXPECT_THAT(diagnostic.reason, HasSubstr("loads version " + std::to_string(kPluginApiVersion)));
  EXPECT_THAT(diagnostic.reason, HasSubstr("rebuild the plugin"));
  EXPECT_THAT(diagnostic.message(), HasSubstr("libfixture_wrong_api_version.so: "));
  EXPECT_TRUE(loader.listTypes().empty());
  EXPECT_FALSE(isLoaded(caseLibrary("wrong_api_version")));
}

TEST(PluginLoader, AbiSizeMismatchFailsTheCreationThatLoadsIt) {
  PluginLoader loader({caseDir("wrong_abi_size")});
  EXPECT_TRUE(loader.diagnostics().empty());
  ASSERT_TRUE(loader.hasType("fixture/WrongAbiSize"));
  // The handshake stops before the entries (garbage on purpose) are read.
  const std::string message = errorOf([&] { loader.create<FixtureController>("fixture/WrongAbiSize"); });
  EXPECT_THAT(message, HasSubstr("cannot create plugin type 'fixture/WrongAbiSize'"));
  EXPECT_THAT(message, HasSubstr(fs::canonical(caseLibrary("wrong_abi_size")).string() + ": ABI mismatch"));
  EXPECT_THAT(message, HasSubstr("size " + std::to_string(kPluginAbiProbeSize + 8)));
  EXPECT_THAT(message, HasSubstr("expects size " + std::to_string(kPluginAbiProbeSize)));
  const auto diagnostic = diagnosticFor(loader, fs::canonical(caseLibrary("wrong_abi_size")));
  EXPECT_THAT(diagnostic.reason, HasSubstr("ABI mismatch"));
  // A second attempt gives the same answer without loading it again.
  EXPECT_THAT(errorOf([&] { loader.create<FixtureController>("fixture/WrongAbiSize"); }),
              HasSubstr("ABI mismatch"));
}

TEST(PluginLoader, DlopenFailureCarriesTheDynamicLinkerReason) {
  PluginLoader loader({caseDir("undefined_symbol")});
  EXPECT_TRUE(loader.hasType("fixture/NeedsMissingSymbol"));
  const std::string message =
      errorOf([&] { loader.create<FixtureController>("fixture/NeedsMissingSymbol"); });
  EXPECT_THAT(message, HasSubstr("cannot create plugin type 'fixture/NeedsMissingSymbol'"));
  EXPECT_THAT(message, HasSubstr("libfixture_undefined_symbol.so: cannot be loaded (dlopen)"));
  EXPECT_THAT(message, HasSubstr("undefined symbol: servoloop_fixture_symbol_defined_nowhere"));
  const auto diagnostic = diagnosticFor(loader, fs::canonical(caseLibrary("undefined_symbol")));
  EXPECT_THAT(diagnostic.reason, HasSubstr("cannot be loaded (dlopen)"));
}

TEST(PluginLoader, FilesThatAreNotElfLibrariesArePassedOverQuietly) {
  const servoloop::testing::TempDir temp("servoloop-plugin-loader");
  const fs::path& dir = temp.path();
  std::ofstream(dir / "libnotes.so") << "this is a text file\n";
  std::ofstream(dir / "libtruncated.so") << "\x7f" "ELF\x02\x01\x01";
  std::ofstream(dir / "README.txt") << "not a library name, never opened\n";
  PluginLoader loader({dir});
  EXPECT_TRUE(loader.diagnostics().empty());
  EXPECT_TRUE(loader.listTypes().empty());
}

TEST(PluginLoader, DuplicateTypeNamesBothLibrariesAndFirstOnPathWins) {
  PluginLoader loader({caseDir("good"), caseDir("duplicate")});
  const fs::path good = fs::canonical(caseLibrary("good"));
  const fs::path duplicate = fs::canonical(caseLibrary("duplicate"));
  const auto diagnostic = diagnosticFor(loader, duplicate);
  EXPECT_THAT(diagnostic.reason, HasSubstr("duplicate type 'fixture/Alpha'"));
  EXPECT_THAT(diagnostic.reason, HasSubstr(good.string()));
  EXPECT_THAT(diagnostic.message(), HasSubstr(duplicate.string()));

  EXPECT_EQ(loader.create<FixtureController>("fixture/Alpha")->name(), "alpha");
  // The clash does not cost the duplicate library its other type.
  EXPECT_EQ(loader.create<FixtureController>("fixture/Delta")->name(), "delta");

  // Reversed path order, reversed winner.
  PluginLoader reversed({caseDir("duplicate"), caseDir("good")});
  EXPECT_EQ(reversed.create<FixtureController>("fixture/Alpha")->name(), "other alpha");
  EXPECT_THAT(diagnosticFor(reversed, good).reason, HasSubstr(duplicate.string()));
}

TEST(PluginLoader, BrokenLibrariesDoNotStopTheOthers) {
  PluginLoader loader({caseDir("not_a_plugin"), caseDir("wrong_api_version"), caseDir("wrong_abi_size"),
                       caseDir("undefined_symbol"), caseDir("aborting_constructor"), caseDir("good")});
  // Only the index from another API version is refused while scanning.
  EXPECT_EQ(loader.diagnostics().size(), 1u);
  EXPECT_EQ(loader.listTypes().size(), 7u);
  EXPECT_EQ(loader.create<FixtureController>("fixture/Beta")->name(), "beta");

  // A broken library fails only the creation that loads it.
  EXPECT_THAT(errorOf([&] { loader.create<FixtureController>("fixture/NeedsMissingSymbol"); }),
              HasSubstr("libfixture_undefined_symbol.so"));
  EXPECT_THAT(errorOf([&] { loader.create<FixtureController>("fixture/WrongAbiSize"); }),
              HasSubstr("libfixture_wrong_abi_size.so"));
  EXPECT_EQ(loader.create<FixtureController>("fixture/Alpha")->name(), "alpha");
  EXPECT_EQ(loader.diagnostics().size(), 3u);

  // The unknown-type error also mentions what failed, as a hint.
  const std::string message = errorOf([&] { loader.create<FixtureController>("fixture/Gamma"); });
  EXPECT_THAT(message, HasSubstr("3 problem(s) while loading plugins"));
  EXPECT_THAT(message, HasSubstr("libfixture_undefined_symbol.so"));
  EXPECT_FALSE(isLoaded(caseLibrary("aborting_constructor")));
}

TEST(PluginLoader, ReloadIsRefusedWhileObjectsLiveUnlessForced) {
  PluginLoader loader({caseDir("good")});
  auto alpha = loader.create<FixtureController>("fixture/Alpha");
  EXPECT_EQ(loader.liveObjectCount(), 1u);
  const std::string message = errorOf([&] { loader.reload(); });
  EXPECT_THAT(message, HasSubstr("cannot reload plugin libraries: 1 object(s)"));
  EXPECT_THAT(errorOf([&] { loader.unloadAll(); }), HasSubstr("cannot unload plugin libraries"));

  loader.reload(/*force=*/true);
  EXPECT_EQ(loader.listTypes().size(), 4u);
  EXPECT_EQ(alpha->name(), "alpha");  // still valid: it holds its library
  alpha.reset();
  EXPECT_EQ(loader.liveObjectCount(), 0u);

  loader.unloadAll();
  EXPECT_TRUE(loader.listTypes().empty());
  loader.reload();
  EXPECT_EQ(loader.listTypes().size(), 4u);
}

TEST(PluginLoader, ReloadPicksUpLibrariesAddedSinceTheLastScan) {
  const servoloop::testing::TempDir temp("servoloop-plugin-loader");
  const fs::path& dir = temp.path();
  PluginLoader loader({dir});
  EXPECT_TRUE(loader.listTypes().empty());
  // A copy under another name: a different file to the dynamic linker.
  fs::copy_file(caseLibrary("duplicate"), dir / "libfixture_copy.so");
  loader.reload();
  EXPECT_TRUE(loader.hasType("fixture/Delta"));
  loader.unloadAll();
}

}  // namespace
}  // namespace servoloop::plugin
