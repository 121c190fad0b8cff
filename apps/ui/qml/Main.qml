pragma ComponentBehavior: Bound
// The kiosk's window: the status strip on top, the screens in a stack
// below it (home at the bottom), the message bar over them.
import QtQuick
import QtQuick.Controls

ApplicationWindow {
    id: window
    required property DaemonLink link
    // The screen shown first (knoblab-ui --screen): home, or one above it.
    required property string startScreen

    visible: true
    title: "knoblab"
    color: Theme.background
    onWidthChanged: Theme.scale = Math.min(width / 1024, height / 600)
    onHeightChanged: Theme.scale = Math.min(width / 1024, height / 600)

    readonly property var screens: ({
            system: systemScreen
        })

    function open(name) {
        const screen = window.screens[name];
        if (screen === undefined) {
            bar.show("no screen called " + name, "error");
            return;
        }
        stack.push(screen);
    }

    header: StatusStrip {
        link: window.link
        onHomeRequested: stack.pop(null)
    }

    Component {
        id: homeScreen
        HomeScreen {
            link: window.link
            onOpen: screen => window.open(screen)
        }
    }
    Component {
        id: systemScreen
        SystemScreen {
            link: window.link
        }
    }

    StackView {
        id: stack
        anchors.fill: parent
        initialItem: homeScreen
        Component.onCompleted: if (window.startScreen !== "home")
            window.open(window.startScreen)
    }

    MessageBar {
        id: bar
        anchors.left: parent.left
        anchors.right: parent.right
        anchors.bottom: parent.bottom
        anchors.margins: Theme.gap
    }
    Connections {
        target: window.link
        function onMessage(text: string, level: string) {
            bar.show(text, level);
        }
    }
}
