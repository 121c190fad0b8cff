pragma ComponentBehavior: Bound
// The kiosk's window: the status strip on top, the screens in a stack
// below it (home at the bottom), the message bar over them.
import QtQuick
import QtQuick.Controls
import QtQuick.VirtualKeyboard

ApplicationWindow {
    id: window
    required property DaemonLink link
    required property KnobLibrary knobs
    required property JobRunner jobs
    required property TelemetryFeed feed
    required property StudySession study
    required property DesignSession designs
    // The screen shown first (knoblab-ui --screen): home, or one above it.
    required property string startScreen

    visible: true
    title: "knoblab"
    Component.onCompleted: window.knobs.refresh()
    color: Theme.background
    onWidthChanged: Theme.scale = Math.min(width / 1024, height / 600)
    onHeightChanged: Theme.scale = Math.min(width / 1024, height / 600)

    readonly property var screens: ({
            system: systemScreen,
            library: libraryScreen,
            capture: captureScreen,
            review: reviewScreen,
            compare: compareScreen,
            study: studyScreen,
            participant: participantScreen,
            prototyper: prototyperScreen
        })
    // The participant's view takes the whole screen: no status strip, no message bar.
    readonly property bool participantView: stack.currentItem !== null && stack.currentItem.objectName === "participantScreen"

    function open(name, properties) {
        const screen = window.screens[name];
        if (screen === undefined) {
            bar.show("no screen called " + name, "error");
            return;
        }
        stack.push(screen, properties !== undefined ? properties : {});
    }
    // The capture a screen opened with --screen shows first (the newest).
    function newestCapture(): int {
        return window.knobs.entries.length > 0 ? window.knobs.entries[0].capture_id : 0;
    }
    // The one before it (compare: the two newest, when opened with --screen).
    function secondNewestCapture(): int {
        return window.knobs.entries.length > 1 ? window.knobs.entries[1].capture_id : 0;
    }

    header: StatusStrip {
        visible: !window.participantView
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
    Component {
        id: captureScreen
        CaptureScreen {
            link: window.link
            knobs: window.knobs
            jobs: window.jobs
            feed: window.feed
            keyboardUp: keyboard.active
            onOpenLibrary: captureId => {
                stack.pop(null);
                stack.push(libraryScreen, { captureId: captureId });
            }
        }
    }
    Component {
        id: libraryScreen
        LibraryScreen {
            knobs: window.knobs
            jobs: window.jobs
            link: window.link
            onReview: captureId => window.open("review", { captureId: captureId })
            onCompare: (a, b) => window.open("compare", { captureA: a, captureB: b })
        }
    }
    Component {
        id: compareScreen
        CompareScreen {
            knobs: window.knobs
            jobs: window.jobs
            captureA: window.newestCapture()
            captureB: window.secondNewestCapture()
        }
    }
    Component {
        id: studyScreen
        StudyScreen {
            study: window.study
            keyboardUp: keyboard.active
            onParticipantView: window.open("participant")
        }
    }
    Component {
        id: participantScreen
        ParticipantScreen {
            study: window.study
            onLeave: stack.pop()
        }
    }
    Component {
        id: prototyperScreen
        PrototyperScreen {
            session: window.designs
            keyboardUp: keyboard.active
        }
    }
    Component {
        id: reviewScreen
        ReviewScreen {
            knobs: window.knobs
            captureId: window.newestCapture()
        }
    }

    // The message bar takes its own room at the bottom: it never covers a
    // button of the screen above it.
    StackView {
        id: stack
        anchors.left: parent.left
        anchors.right: parent.right
        anchors.top: parent.top
        // Above the keyboard while it is up: the field being typed in stays in sight.
        anchors.bottom: keyboard.active ? keyboard.top : bar.visible && !window.participantView ? bar.top : parent.bottom
        anchors.bottomMargin: bar.visible && !keyboard.active && !window.participantView ? Theme.gap : 0
        initialItem: homeScreen
        Component.onCompleted: if (window.startScreen !== "home")
            window.open(window.startScreen)
    }

    MessageBar {
        id: bar
        // Not for the participant's eyes: it waits under their view.
        opacity: window.participantView ? 0 : 1
        enabled: !window.participantView
        anchors.left: parent.left
        anchors.right: parent.right
        anchors.bottom: parent.bottom
        anchors.margins: Theme.gap
    }
    // The on-screen keyboard (Qt Virtual Keyboard, in-app: knoblab-ui selects
    // it as the input method) rises when a text field takes focus.
    InputPanel {
        id: keyboard
        objectName: "keyboard"
        z: 2
        // Its height follows its width: on a wide, short panel a full-width
        // keyboard would take half the screen.
        width: Math.min(parent.width, parent.height * 1.6)
        x: (parent.width - width) / 2
        y: keyboard.active ? parent.height - keyboard.height : parent.height
        visible: keyboard.active
    }

    Connections {
        target: window.link
        function onMessage(text: string, level: string) {
            bar.show(text, level);
        }
        function onEvent(name: string, data: var) {
            if (name === "capture_finished")
                window.knobs.refresh();
        }
    }
    Connections {
        target: window.study
        function onMessage(text: string, level: string) {
            bar.show(text, level);
        }
    }
    Connections {
        target: window.designs
        function onMessage(text: string, level: string) {
            bar.show(text, level);
        }
    }
    Connections {
        target: window.knobs
        function onMessage(text: string, level: string) {
            bar.show(text, level);
        }
    }
    Connections {
        target: window.jobs
        function onMessage(text: string, level: string) {
            bar.show(text, level);
        }
        function onFinished(kind: string, captureId: int, ok: bool, result: var, error: string) {
            if (kind === "compare")
                return;  // nothing stored: the comparison screen shows it, or why not
            window.knobs.refresh();
            bar.show(ok ? kind + " of capture " + captureId + " stored" : kind + " of capture " + captureId + ": " + error,
                     ok ? "info" : "warning");
        }
    }
}
