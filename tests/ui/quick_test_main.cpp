// QtQuickTest's runner for tests/ui/qml/tst_*.qml.
#include <QtQuickTest/quicktest.h>

QUICK_TEST_MAIN(knoblab_ui)
